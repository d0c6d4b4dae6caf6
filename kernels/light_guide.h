// A record's rays aimed at the light guide's clusters (docs/ALGORITHM.md section 4 samples the hemisphere uniformly in
// projected solid angle; a small bright patch that covers part of one stratum is then found by a few records only,
// each of which turns it into a bright disc: the blotches of issue 10). Each record picks clusters in proportion to
// the irradiance they could give it and samples directions uniformly in the cone each one subtends. Both kinds of ray
// are combined by the balance heuristic (Veach 1997, multi-sample MIS), so the estimate stays unbiased wherever the
// guide is wrong: a cone that is occluded or dark only costs rays.
#ifndef RCSPLAT_LIGHT_GUIDE_H
#define RCSPLAT_LIGHT_GUIDE_H
#include "low_discrepancy.h"
#include "sampling.h"
#include "shared_types.h"

typedef struct {
  float3 axis;      // from the record to the cluster's centre
  float cos_max;    // cosine of the cone's half-angle
  float inv_solid_angle;
  float promise;    // the cluster's estimated irradiance here
  float cdf;        // inclusive selection probability
} GuideCone;

// 1 - sqrt(1 - x) without cancellation for small x (tiny cones).
inline float one_minus_sqrt_one_minus(float x) { return x / (1.0f + sqrt(fmax(1.0f - x, 0.0f))); }

// A rough estimate of the irradiance cluster g gives point p (normal n): its flux leaving a disc, cos cos' / (pi d^2),
// visibility ignored, the distance kept above the cluster's radius. Only the guide's choices use it.
inline float guide_irradiance_estimate(GuideCluster g, float3 p, float3 n) {
  float3 to = vload3(0, g.centre) - p;
  float d2 = fmax(dot(to, to), g.radius * g.radius);
  float d = sqrt(d2);
  float3 axis = to / d;
  float cos_record = clamp(dot(axis, n) + g.radius / d, 0.0f, 1.0f);  // the sphere's nearest edge may be above the plane
  float3 cn = vload3(0, g.normal);
  // A cluster lit on one side gives nothing behind it; one whose normals spread (mean shorter than 1) faces every way.
  float cos_cluster = clamp(-dot(cn, axis) + (1.0f - fmin(length(cn), 1.0f)) + g.radius / d, 0.0f, 1.0f);
  return luminance(vload3(0, g.flux)) * cos_record * cos_cluster * RC_INV_PI / d2;
}

// Drops the cones that promise nothing and makes the rest's selection probabilities proportional to their promises
// (inclusive cdf, the last exactly 1). Returns how many are left.
inline uint guide_selection_cdf(GuideCone* cones, uint count) {
  uint kept = 0;
  float total = 0.0f;
  for (uint c = 0; c < count; ++c)
    if (cones[c].promise > 0.0f) {
      total += cones[c].promise;
      cones[kept++] = cones[c];
    }
  float running = 0.0f;
  for (uint c = 0; c < kept; ++c) {
    running += cones[c].promise;
    cones[c].cdf = running / total;
  }
  if (kept) cones[kept - 1].cdf = 1.0f;
  return kept;
}

// The cones of the clusters worth aiming at from a record at p (normal n): those that look small (a solid angle of at
// most max_solid_angle: the strata find anything larger often enough) and promise at least GUIDE_MIN_SHARE of the
// irradiance all clusters together promise. Selection probabilities are proportional to those promises. Returns the
// number of cones (0: the record takes no guided rays), at most GUIDE_MAX_CONES: those that promise most (the first
// in the clusters' order among equals).
inline uint guide_cones(__global const GuideCluster* clusters, uint count, float3 p, float3 n, float max_solid_angle,
                        GuideCone* cones) {
  float promise[GUIDE_MAX_CLUSTERS], promised = 0.0f;
  for (uint c = 0; c < count; ++c) promised += promise[c] = guide_irradiance_estimate(clusters[c], p, n);
  uint kept = 0;
  for (uint c = 0; c < count; ++c) {
    GuideCluster g = clusters[c];
    float w = promise[c];
    if (!(w >= GUIDE_MIN_SHARE * promised) || !(w > 0.0f)) continue;
    float3 to = vload3(0, g.centre) - p;
    float d2 = dot(to, to), r2 = g.radius * g.radius;
    if (!(d2 > 1.5f * r2)) continue;  // inside or at the sphere: it fills much of the hemisphere
    float one_minus_cos = one_minus_sqrt_one_minus(r2 / d2);
    if (2.0f * RC_PI * one_minus_cos > max_solid_angle) continue;
    if (kept == GUIDE_MAX_CONES && !(w > cones[kept - 1].promise)) continue;
    uint at = kept < GUIDE_MAX_CONES ? kept++ : kept - 1;  // insertion into the list sorted by promise
    while (at > 0 && cones[at - 1].promise < w) {
      cones[at] = cones[at - 1];
      --at;
    }
    cones[at].axis = to * rsqrt(d2);
    cones[at].cos_max = 1.0f - one_minus_cos;
    cones[at].inv_solid_angle = 1.0f / (2.0f * RC_PI * one_minus_cos);
    cones[at].promise = w;
  }
  return guide_selection_cdf(cones, kept);
}

// A record's cones, found once (guide_cones) and read by each of its rays.
inline void store_guide_cones(const GuideCone* cones, uint count, __global RecordGuideCones* stored) {
  for (uint c = 0; c < count; ++c) {
    vstore3(cones[c].axis, 0, stored->cones[c].axis);
    stored->cones[c].cos_max = cones[c].cos_max;
    stored->cones[c].inv_solid_angle = cones[c].inv_solid_angle;
    stored->cones[c].promise = cones[c].promise;
    stored->cones[c].cdf = cones[c].cdf;
    stored->cones[c].pad = 0.0f;
  }
  stored->count = count;
}

inline float guide_selection(const GuideCone* cones, uint c) { return cones[c].cdf - (c > 0 ? cones[c - 1].cdf : 0.0f); }

// One cone's share of the guide's density at dir: its selection probability over its solid angle, where dir lies in it
// or the guide drew dir from it (drew).
inline float cone_density(float3 axis, float cos_max, float selection, float inv_solid_angle, float3 dir, bool drew) {
  return drew || dot(dir, axis) >= cos_max ? selection * inv_solid_angle : 0.0f;
}

// The guide's density (per solid angle) of direction dir: the cones that contain it. For a direction the guide drew
// from cone `drawn_from` (else GUIDE_MAX_CONES), that cone counts whatever the rounded test says: a direction on the
// rim of a tiny cone may test outside it, and its weight would then divide by the other technique's density alone.
inline float guide_pdf_drawn(const GuideCone* cones, uint count, float3 dir, uint drawn_from) {
  float pdf = 0.0f;
  for (uint c = 0; c < count; ++c)
    pdf += cone_density(cones[c].axis, cones[c].cos_max, guide_selection(cones, c), cones[c].inv_solid_angle, dir,
                        c == drawn_from);
  return pdf;
}

// The direction at 1 - cos(theta) = one_minus_cos from axis and at azimuth 2 pi w about it: with one_minus_cos
// uniform in [0, 1 - cos_max], a direction uniform in the cone of half-angle acos(cos_max).
inline float3 cone_direction(float3 axis, float one_minus_cos, float w) {
  float cos_t = 1.0f - one_minus_cos;
  float sin_t = sqrt(fmax(one_minus_cos * (2.0f - one_minus_cos), 0.0f));
  float cos_p, sin_p = sincos(2.0f * RC_PI * w, &cos_p);
  float3 t, b;
  tangent_frame(axis, &t, &b);
  return (cos_p * sin_t) * t + (sin_p * sin_t) * b + cos_t * axis;
}

// A direction from the guide: a cone picked by u (into *drawn_from), uniform inside it by (v, w).
inline float3 sample_guide(const GuideCone* cones, uint count, float u, float v, float w, uint* drawn_from) {
  uint c = 0;
  while (c + 1 < count && u >= cones[c].cdf) ++c;
  *drawn_from = c;
  return cone_direction(cones[c].axis, v * (1.0f - cones[c].cos_max), w);
}

// A record's stored cones, read where they lie by each of its rays (kernels/records.cl) rather than copied: the
// record's work-items read the same bytes, and a private copy of GUIDE_MAX_CONES cones took 256 bytes of each
// work-item's stack on a GPU. The same numbers as guide_pdf_drawn and sample_guide on such a copy.
inline uint stored_cone_count(__global const RecordGuideCones* stored) {
  return min(stored->count, (uint)GUIDE_MAX_CONES);
}

inline float stored_guide_pdf_drawn(__global const RecordGuideCones* stored, float3 dir, uint drawn_from) {
  float pdf = 0.0f, previous_cdf = 0.0f;
  for (uint c = 0; c < stored_cone_count(stored); ++c) {
    __global const StoredGuideCone* cone = stored->cones + c;
    pdf += cone_density(vload3(0, cone->axis), cone->cos_max, cone->cdf - previous_cdf, cone->inv_solid_angle, dir,
                        c == drawn_from);
    previous_cdf = cone->cdf;
  }
  return pdf;
}

inline float3 sample_stored_guide(__global const RecordGuideCones* stored, float u, float v, float w,
                                  uint* drawn_from) {
  const uint count = stored_cone_count(stored);
  uint c = 0;
  while (c + 1 < count && u >= stored->cones[c].cdf) ++c;
  *drawn_from = c;
  return cone_direction(vload3(0, stored->cones[c].axis), v * (1.0f - stored->cones[c].cos_max), w);
}

#endif
