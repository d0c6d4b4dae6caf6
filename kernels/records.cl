// Record computation (ALGORITHM.md sections 4 and 5): for each candidate pixel, M x N stratified cosine-weighted rays
// over the hemisphere of its G-buffer point give the irradiance E, Ward's harmonic mean distance (the validity radius,
// clamped in screen space) and Ward & Heckbert's rotational and translational gradients, bounded.
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#include "bounce.h"
#include "cache_math.h"
#include "light_guide.h"

// The host compiles this kernel with THETA_STRATA_CAPACITY = the largest M it will ask for (at most
// HEMISPHERE_MAX_THETA_STRATA): one column of M strata lives in private memory, so it is sized to M. With
// STORE_STRATA = 1 (radiance caching) each stratum's radiance (the share the light guide leaves it) and hit distance
// are also kept, for the HSH projection of kernels/hsh_records.cl, and the record casts no guided rays.

// gradient[axis] += direction[axis] * value, for a world-space direction and an RGB value.
inline void add_outer(float3* gradient, float3 direction, float3 value) {
  gradient[0] += direction.x * value;
  gradient[1] += direction.y * value;
  gradient[2] += direction.z * value;
}

// Scales the per-channel gradient rows so that no channel's gradient is longer than limit (per channel).
inline void bound_gradient(float3* gradient, float3 limit) {
  float3 len = sqrt(gradient[0] * gradient[0] + gradient[1] * gradient[1] + gradient[2] * gradient[2]);
  float3 scale = select((float3)(1.0f), limit / len, len > limit);
  for (int a = 0; a < 3; ++a) gradient[a] = finite_or_zero(gradient[a] * scale);
}

// The guide's share of E (kernels/light_guide.h): guided_rays rays into the record's cones, each weighted
// f / (n_c p_c + n_g p_g) with f = L cos(theta) (the balance heuristic beside the strata's cosine density). Their
// random numbers follow the strata's, from sample M N on.
inline float3 guided_irradiance(SCENE_ARGS GATHER_MAP_ARGS, float3 origin, float3 n, float3 ng, const GuideCone* cones,
                                uint cone_count, uint guided_rays, float cosine_density, uint key, uint first_sample,
                                uint bounces, uint* rays) {
  float3 e = (float3)(0.0f);
  for (uint g = 0; g < guided_rays; ++g) {
    uint s = first_sample + g;
    uint drawn_from;
    float3 dir = sample_guide(cones, cone_count, random01(key, s, 5u), random01(key, s, 0u), random01(key, s, 1u),
                              &drawn_from);
    float cos_n = dot(dir, n);
    if (cos_n <= 0.0f || dot(dir, ng) <= 0.0f) continue;
    float r;
    float3 l = bounce_radiance(SCENE GATHER_MAP, origin, dir, random01(key, s, 2u), random01(key, s, 3u), random01(key, s, 4u),
                               path_continuation(key, s, bounces), &r, rays);
    e += l * (cos_n / (cosine_density * cos_n +
                       (float)guided_rays * guide_pdf_drawn(cones, cone_count, dir, drawn_from)));
  }
  return e;
}

__kernel void compute_records(SCENE_ARGS GATHER_MAP_ARGS, GBUFFER_ARGS, __global const uint* candidates, RecordBatchParams batch,
                              __global CacheRecord* records,
                              __global const GuideCluster* guide,
#if STORE_STRATA
                              __global float4* strata,
#endif
                              __global ulong* ray_total) {
  uint i = get_global_id(0);
  if (i >= batch.candidate_count) return;
  const HemisphereParams hp = batch.hemisphere;
  uint pixel = candidates[i];
  GBufferSample g = gbuffer[pixel];
  float3 p = vload3(0, g.position), n = vload3(0, g.normal), ng = vload3(0, g.geometric_normal);
  float3 origin = offset_ray_origin(p, ng);
  float3 t, b;
  tangent_frame(n, &t, &b);  // the frame the horizon sectors are measured in
  const uint M = hp.theta_strata, N = hp.phi_strata;
  const float inv_m = 1.0f / (float)M, dphi = 2.0f * RC_PI / (float)N;
  uint key = hash_u32(pixel ^ hash_u32(hp.seed));

  // The light guide's cones for this record (none without a guide): its rays and the strata are weighted by the
  // balance heuristic, each sample's weight its technique's share of the combined density n_c p_c + n_g p_g.
  GuideCone cones[GUIDE_MAX_CONES];
  const float cosine_density = (float)(M * N) * RC_INV_PI;  // n_c p_c / cos(theta)
  // A cone larger than GUIDE_MAX_STRATA strata' worth of solid angle is found often enough by the strata themselves.
  const uint cone_count =
      hp.guide_rays ? guide_cones(guide, hp.guide_clusters, p, n, GUIDE_MAX_STRATA / cosine_density, cones) : 0u;
  const float guided_rays = (float)hp.guide_rays;

  // Per-row weights, the same in every column: computed once. theta_wall: the wall between rows j - 1 and j, at
  // theta_j- (sin theta cos^2 theta dphi); phi_wall: the integral of cos(theta) over row j (the walls between columns);
  // rotation: the integral of sin^2(theta) over row j. Tilting n by d about axis a changes E by d times the integral
  // of L sin(theta) (a . v(phi)) dw; integrating that weight over each stratum (rather than Ward and Heckbert's
  // per-sample tan(theta), whose variance is unbounded in the row at the horizon) leaves no gradient at all in a
  // uniform environment.
  float theta_wall[THETA_STRATA_CAPACITY], phi_wall[THETA_STRATA_CAPACITY], rotation_weight[THETA_STRATA_CAPACITY];
  for (uint j = 0; j < M; ++j) {
    float sin_lo = sqrt((float)j * inv_m), cos_lo = sqrt(1.0f - (float)j * inv_m);
    float sin_hi = sqrt((float)(j + 1) * inv_m), cos_hi = sqrt(fmax(1.0f - (float)(j + 1) * inv_m, 0.0f));
    theta_wall[j] = dphi * sin_lo * cos_lo * cos_lo;
    phi_wall[j] = sin_hi - sin_lo;
    rotation_weight[j] = 0.5f * (asin(sin_hi) - asin(sin_lo)) - 0.5f * (sin_hi * cos_hi - sin_lo * cos_lo);
  }

  // Stratum (j, k) needs (j - 1, k) and (j, k - 1): keep the previous column, and the first for the wrap-around.
  float3 prev_l[THETA_STRATA_CAPACITY], first_l[THETA_STRATA_CAPACITY];
  float prev_r[THETA_STRATA_CAPACITY], first_r[THETA_STRATA_CAPACITY];
  float3 e = (float3)(0.0f);
  float3 grad_t[3] = {(float3)(0.0f), (float3)(0.0f), (float3)(0.0f)};
  float3 grad_r[3] = {(float3)(0.0f), (float3)(0.0f), (float3)(0.0f)};
  float inverse_distances = 0.0f;
  // The horizon: per column, the nearest occluder the low rows (elevation below 30 degrees) found, measured along the
  // tangent plane; per sector, the nearest of its columns' (conservative: a wall seen obliquely hides the whole sector
  // beyond it).
  const uint first_low_row = (uint)ceil(HORIZON_MIN_SIN2_THETA * (float)M);
  float horizon[RECORD_HORIZON_SECTORS];
  for (int s = 0; s < RECORD_HORIZON_SECTORS; ++s) horizon[s] = INFINITY;
  uint rays = 0;
  for (uint k = 0; k < N; ++k) {
    float cos_mid, sin_mid = sincos(((float)k + 0.5f) * dphi, &cos_mid);
    float cos_lo, sin_lo = sincos((float)k * dphi, &cos_lo);
    float3 u_mid = cos_mid * t + sin_mid * b, v_mid = -sin_mid * t + cos_mid * b, v_lo = -sin_lo * t + cos_lo * b;
    float3 rotation = (float3)(0.0f), l_below = (float3)(0.0f);
    float r_below = INFINITY, column_horizon = INFINITY;
    for (uint j = 0; j < M; ++j) {
      uint s = j * N + k;
      float sin2 = ((float)j + random01(key, s, 0u)) * inv_m;
      float sin_t = sqrt(sin2), cos_t = sqrt(1.0f - sin2);
      float cos_phi, sin_phi = sincos(((float)k + random01(key, s, 1u)) * dphi, &cos_phi);
      float3 dir = (cos_phi * sin_t) * t + (sin_phi * sin_t) * b + cos_t * n;
      float r = INFINITY;
      float3 l = (float3)(0.0f);
      if (dot(dir, ng) > 0.0f) {  // a direction below the geometric surface sees nothing
        l = bounce_radiance(SCENE GATHER_MAP, origin, dir, random01(key, s, 2u), random01(key, s, 3u), random01(key, s, 4u),
                            path_continuation(key, s, hp.bounces), &r, &rays);
      }
      // What the strata estimate is the part of the light the guide leaves to them; their gradients, and the HSH
      // projection of radiance records, see that part.
      if (cone_count) {
        float c = cosine_density * cos_t;
        l *= c / (c + guided_rays * guide_pdf(cones, cone_count, dir));
      }
#if STORE_STRATA
      strata[((size_t)i * M + j) * N + k] = (float4)(l, r);
#endif
      e += l;
      inverse_distances += 1.0f / r;
      if (j >= first_low_row) column_horizon = fmin(column_horizon, r * sin_t);
      rotation += rotation_weight[j] * l;
      if (j > 0) add_outer(grad_t, u_mid, (theta_wall[j] / fmin(r, r_below)) * (l - l_below));
      if (k > 0) add_outer(grad_t, v_lo, (phi_wall[j] / fmin(r, prev_r[j])) * (l - prev_l[j]));
      else {
        first_l[j] = l;
        first_r[j] = r;
      }
      l_below = l;
      r_below = r;
      prev_l[j] = l;
      prev_r[j] = r;
    }
    add_outer(grad_r, v_mid, (2.0f * sin(0.5f * dphi)) * rotation);  // the integral of v(phi) over the column
    int sector = horizon_sector(cos_mid, sin_mid);
    horizon[sector] = fmin(horizon[sector], column_horizon);
  }
  for (uint j = 0; j < M; ++j)  // the wall at phi = 0 between the last column and the first
    add_outer(grad_t, b, (phi_wall[j] / fmin(first_r[j], prev_r[j])) * (first_l[j] - prev_l[j]));
  float norm = RC_PI / (float)(M * N);
  // Radiance records (STORE_STRATA) cache only the strata's share; each pixel samples the guide's share itself
  // (kernels/glossy.cl guided_share), so that a small bright source never goes through the truncated HSH basis.
  float3 e_guided = (float3)(0.0f);
#if !STORE_STRATA
  if (cone_count)
    e_guided = guided_irradiance(SCENE GATHER_MAP, origin, n, ng, cones, cone_count, hp.guide_rays, cosine_density, key, M * N,
                                 hp.bounces, &rays);
#endif
  e = finite_or_zero(e * norm + e_guided);

  // Radius: Ward's harmonic mean distance, clamped to [min, max] pixel footprints at the record.
  float harmonic = (float)(M * N) / inverse_distances;
  float pixel_size = pixel_world_size(camera, p);
  float radius = clamp(harmonic, hp.min_radius_pixels * pixel_size, hp.max_radius_pixels * pixel_size);
  if (!(radius > 0.0f)) radius = fmax(hp.min_radius_pixels * pixel_size, 1e-30f);
  // Bounded gradients (ALGORITHM.md section 5): translation changes E by at most E across R, rotation by at most E.
  bound_gradient(grad_t, e / radius);
  bound_gradient(grad_r, e);

  CacheRecord rec;
  vstore3(p, 0, rec.position);
  rec.radius = radius;
  vstore3(n, 0, rec.normal);
  rec.pixel = (int)pixel;
  vstore3(e, 0, rec.irradiance);
  rec.pixel_size = pixel_size;
  for (int a = 0; a < 3; ++a) {
    vstore3(grad_t[a], a, rec.grad_translation);
    vstore3(grad_r[a], a, rec.grad_rotation);
  }
  rec.harmonic_distance = harmonic;
  rec.pad = 0.0f;
  // A sector no column falls in (N < 8) hides nothing; a record always reaches its own pixel's half-footprint.
  for (int s = 0; s < RECORD_HORIZON_SECTORS; ++s)
    rec.horizon[s] = fmax(horizon[s], 0.5f * pixel_size);
  records[batch.first_record + i] = rec;
  atom_add(ray_total, (ulong)rays);
}
