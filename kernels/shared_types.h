// Structs shared by the host (C++) and the kernels (OpenCL C): the single source of their layout.
// Every struct is a whole number of 16-byte rows and holds only 4-byte scalars, so both compilers lay it out alike;
// the static_asserts at the end check that on the host side.
#ifndef RCSPLAT_SHARED_TYPES_H
#define RCSPLAT_SHARED_TYPES_H

#ifdef __OPENCL_VERSION__
typedef uint rc_uint;
typedef int rc_int;
#else
#include <cstdint>
typedef std::uint32_t rc_uint;
typedef std::int32_t rc_int;
#endif

// Eight-wide BVH node: the children's boxes as six rows of eight (so a node test is a few float8 operations) and the
// children's references. A reference >= 0 is an inner node's index; < 0 is a leaf, ~ref = first_block << 2 | (blocks - 1).
// An empty slot has an inverted box (lo = +inf, hi = -inf) that no ray can hit.
#define BVH_WIDTH 8
#define BVH_MAX_LEAF_BLOCKS 4
typedef struct {
  float lo_x[8], hi_x[8], lo_y[8], hi_y[8], lo_z[8], hi_z[8];
  rc_int child[8];
} Bvh8Node;

// Eight triangles' vertices stored as rows, intersected together by one float8 watertight test.
// prim = the scene's triangle index; unused lanes have prim = -1 and all-zero vertices (determinant 0: never hit).
typedef struct {
  float v0_x[8], v0_y[8], v0_z[8];
  float v1_x[8], v1_y[8], v1_z[8];
  float v2_x[8], v2_y[8], v2_z[8];
  rc_int prim[8];
} TriangleBlock8;

// Per-triangle data needed only once a ray has hit: the vertices (a hit point interpolated from them is accurate to
// a few ULPs of the coordinates, where origin + t * direction is not), normals, texture coordinates, material.
typedef struct {
  float v0[3];
  rc_uint material;
  float v1[3], v2[3];
  float geometric_normal[3];  // unit, from the winding (v1 - v0) x (v2 - v0)
  float normal0[3], normal1[3], normal2[3];  // unit shading normals at the vertices
  float uv0[2], uv1[2], uv2[2];
  rc_uint color[3];  // vertex colours (glTF COLOR_0), linear RGB, 10 bits each (VERTEX_COLOR_*): read under HAS_VERTEX_COLORS
  rc_int emitter;    // index into the emissive triangles, -1 if this triangle emits nothing (BRDF samples that hit it)
} TriangleShading;

// A vertex colour channel c in [0, 1] is stored as round(c * VERTEX_COLOR_MAX) in bits 10k .. 10k + 9.
#define VERTEX_COLOR_BITS 10
#define VERTEX_COLOR_MAX 1023

#define TEXTURE_NONE (-1)

// How the cache shades a surface's specular lobe (docs/NOTES.md "Material kinds"; material_lobe below decides):
// LOBE_NONE: Lambertian (metallic 0 and no specular layer), exactly base / pi: the irradiance cache is exact for it.
// LOBE_ROUGH: a wide lobe; its indirect light is taken from the cached irradiance, E / pi times the lobe's albedo.
// LOBE_GLOSSY: a lobe too sharp for the highest HSH order; its indirect light is estimated per pixel by sampling the
// lobe (kernels/glossy.cl).
// LOBE_HSH: a glossy lobe that HSH_MAX_ORDER holds: radiance caching (records of incident radiance in hemispherical
// harmonics, kernels/hsh_records.cl, splatted with each pixel's view by kernels/radiance_splat.cl).
#define LOBE_NONE 0
#define LOBE_ROUGH 1
#define LOBE_GLOSSY 2
#define LOBE_HSH 3
#define LOBE_KINDS 4
// A lobe with roughness at or above this is LOBE_ROUGH for a dielectric; metals (metallic >= 0.5) need
// ROUGH_METAL_MIN_ROUGHNESS, since their whole reflection is the lobe.
#define ROUGH_MIN_ROUGHNESS 0.6f
#define ROUGH_METAL_MIN_ROUGHNESS 0.9f
// A glossy lobe with roughness at or above this is radiance-cached (LOBE_HSH): order 10 holds 80% of its energy seen
// at 72 degrees, two thirds at the most grazing view (passes/brdf_table_pass.h captured_energy; docs/NOTES.md
// "Radiance caching" has the measured table). Only roughness shapes the lobe's table, so the bound is the same for
// metals and dielectrics. Sharper lobes are sampled per pixel (LOBE_GLOSSY).
#define HSH_MIN_ROUGHNESS 0.45f

// The cone angle (radians) of a glossy sample's ray, for filtering the textures it finds (kernels/surface.h): the
// default 16 x 32 record strata's, sqrt(2 pi / 512).
#define SECONDARY_CONE_ANGLE 0.1108f

// The rough lobes' albedo table (kernels/brdf_frame.h): cos(theta_o) and roughness at i / (size - 1).
#define SPECULAR_ALBEDO_TABLE_SIZE 32
// The sheen lobe's albedo table (kernels/sheen_albedo_values.h): cos(theta_o) and sheen roughness at i / (size - 1).
#define SHEEN_ALBEDO_TABLE_SIZE 32
// The sheen's alpha = roughness^2 is kept above this: the Charlie distribution's exponent is 1 / alpha.
#define SHEEN_MIN_ALPHA 1.0e-3f

// The LOBE_* of a surface with these parameters (the host for a material's factors, the G-buffer per pixel).
inline rc_int material_lobe(float metallic, float roughness, float specular) {
  if (!(metallic > 0.0f) && !(specular > 0.0f)) return LOBE_NONE;
  float rough_from = metallic >= 0.5f ? ROUGH_METAL_MIN_ROUGHNESS : ROUGH_MIN_ROUGHNESS;
  if (roughness >= rough_from) return LOBE_ROUGH;
  return roughness >= HSH_MIN_ROUGHNESS ? LOBE_HSH : LOBE_GLOSSY;
}

typedef struct {
  float base_color[4];  // linear RGBA factor
  float emission[3];    // emissiveFactor x emissive strength, linear RGB radiance
  rc_int base_color_texture;  // index into the texture table or TEXTURE_NONE
  rc_int double_sided;
  float alpha_cutoff;  // glTF alpha mode MASK: alpha below it is a hole; 0 for opaque materials
  float metallic;      // glTF metallicFactor
  float roughness;     // glTF roughnessFactor
  float specular;      // KHR_materials_specular's specularFactor: weight of a dielectric's specular layer (glTF: 1)
  rc_int metallic_roughness_texture;  // glTF's metallicRoughnessTexture (B: metallic, G: roughness) or TEXTURE_NONE
  rc_int lobe;         // LOBE_* for the factors; a texture's roughness is classified again per pixel
  rc_int emissive_texture;  // glTF's emissiveTexture (sRGB), times emission; TEXTURE_NONE: emission is uniform
  rc_int normal_texture;    // glTF's normalTexture (tangent space, linear) or TEXTURE_NONE (kernels/surface.h)
  float normal_scale;       // glTF's normalTexture.scale: multiplies the map's x and y
  rc_int alpha_blend;       // glTF alpha mode BLEND: a point is a hole with probability 1 - alpha (kernels/traverse.h)
  rc_int specular_texture;  // KHR_materials_specular's specularTexture (its A multiplies specular) or TEXTURE_NONE
  // Glass (kernels/glass.h): KHR_materials_transmission's factor (0: opaque) and texture (its R multiplies it);
  // KHR_materials_ior; KHR_materials_volume's thicknessFactor (0: thin-walled, rays pass straight; above 0 the mesh
  // bounds a volume and rays refract) and its Beer-Lambert coefficient per unit length, -ln(attenuationColor) /
  // attenuationDistance (0: clear).
  float transmission;
  rc_int transmission_texture;
  float ior;
  float thickness;
  float attenuation[3];
  rc_int layered;  // 1: a layer below is present (specular colour not white, clearcoat or sheen): HAS_LAYERS shades it
  // Layers (kernels/brdf_layers.h, HAS_LAYERS). KHR_materials_specular's colour, which tints the dielectric's F0
  // (0.04 x colour, at most 1), and its texture (sRGB, RGB multiplies it).
  float specular_color[3];
  rc_int specular_color_texture;
  // KHR_materials_clearcoat: the coat's weight and its texture (R), roughness and its texture (G), and its normal
  // texture and scale (TEXTURE_NONE: the coat follows the interpolated normal, not the base's normal map).
  float clearcoat;
  rc_int clearcoat_texture;
  float clearcoat_roughness;
  rc_int clearcoat_roughness_texture;
  rc_int clearcoat_normal_texture;
  float clearcoat_normal_scale;
  // KHR_materials_sheen: roughness and its texture (A), colour (0: no sheen) and its texture (sRGB, RGB).
  float sheen_roughness;
  rc_int sheen_roughness_texture;
  float sheen_color[3];
  rc_int sheen_color_texture;
} Material;

// A surface point's layers (kernels/brdf_layers.h): what the material and its textures make there. The G-buffer keeps
// one a pixel beside its GBufferSample (HAS_LAYERS; one unread element otherwise).
typedef struct {
  float specular_color[3];  // the F0 tint, 1 without KHR_materials_specular's colour
  float clearcoat;          // the coat's weight, 0: none
  float coat_normal[3];     // world space, facing the viewer as the shading normal
  float clearcoat_roughness;
  float sheen_color[3];     // 0: no sheen
  float sheen_roughness;
} SurfaceLayers;

// The LOBE_* of a layered surface whose base alone is `base` (material_lobe). The HSH table holds the base lobe alone,
// so a layered surface is never LOBE_HSH: its lobes are sampled per pixel (LOBE_GLOSSY) unless all are wide
// (LOBE_ROUGH: a sheen, a coat of roughness ROUGH_MIN_ROUGHNESS or more, and a rough base).
inline rc_int layered_lobe(rc_int base, float clearcoat, float clearcoat_roughness, float sheen) {
  rc_int lobe = base == LOBE_HSH ? LOBE_GLOSSY : base;
  if (sheen > 0.0f && lobe == LOBE_NONE) lobe = LOBE_ROUGH;
  if (clearcoat > 0.0f) {
    const rc_int coat = clearcoat_roughness >= ROUGH_MIN_ROUGHNESS ? LOBE_ROUGH : LOBE_GLOSSY;
    if (coat > lobe) lobe = coat;
  }
  return lobe;
}

#define WRAP_REPEAT 0
#define WRAP_CLAMP 1
#define WRAP_MIRROR 2
#define TEXTURE_NEAREST (1u << 16)  // in TextureInfo.wrap: the nearest texel instead of bilinear filtering
#define TEXTURE_LEVELS_SHIFT 20     // in TextureInfo.wrap: how many mip levels follow each other from first_texel
// TextureInfo.wrap, packed by the host and read by kernels/surface.h.
inline rc_uint texture_wrap(rc_uint wrap_s, rc_uint wrap_t, int nearest, rc_uint levels) {
  return wrap_s | wrap_t << 8 | (nearest ? TEXTURE_NEAREST : 0u) | levels << TEXTURE_LEVELS_SHIFT;
}
inline rc_uint texture_wrap_s(rc_uint wrap) { return wrap & 255u; }
inline rc_uint texture_wrap_t(rc_uint wrap) { return (wrap >> 8) & 255u; }
inline rc_uint texture_levels(rc_uint wrap) { return wrap >> TEXTURE_LEVELS_SHIFT; }
// A mip level's side: the level above's halved, rounded down, at least 1.
inline rc_uint texture_level_side(rc_uint side, rc_uint level) { return side >> level > 0u ? side >> level : 1u; }
typedef struct {
  rc_uint first_texel;  // offset into the RGBA8 (sRGB-encoded) texel array: level 0, then each smaller level
  rc_uint width, height;  // level 0's
  rc_uint wrap;  // texture_wrap(): wrap_s | wrap_t << 8, | TEXTURE_NEAREST, | levels << TEXTURE_LEVELS_SHIFT
} TextureInfo;

#define LIGHT_POINT 0
#define LIGHT_SPOT 1
#define LIGHT_DIRECTIONAL 2
typedef struct {
  float position[3];
  rc_int type;
  float direction[3];  // unit, the direction light travels (spot and directional)
  float range;         // 0 = infinite
  float intensity[3];  // colour x intensity: candela (point, spot) or lux (directional)
  float spot_scale;    // glTF's smooth cone falloff: saturate(cos * scale + offset)^2
  float spot_offset;
  float pad[3];
} PunctualLight;

// One emissive triangle, sampled as an area light in proportion to its emitted power (half; half by area).
typedef struct {
  float v0[3];
  float area;
  float edge1[3];
  float cdf;  // inclusive cumulative selection probability
  float edge2[3];
  float pdf_select;  // probability of choosing this triangle
  float radiance[3];  // the material's emission (emissiveFactor x strength); with a texture, times its texels
  // Bit 0: double-sided. Above it, textured_triangle + 1: the TriangleShading whose material's emissive texture
  // multiplies radiance where a sample lands (0: untextured). Packed so that the struct stays four rows.
  rc_int sides_and_texture;
} EmissiveTriangle;
inline rc_int emitter_double_sided(EmissiveTriangle e) { return e.sides_and_texture & 1; }
// The emitter's triangle where its emission is textured, else -1.
inline rc_int emitter_textured_triangle(EmissiveTriangle e) { return (e.sides_and_texture >> 1) - 1; }

// Perspective: rays from eye through the image plane at distance 1 (half height tan_half_fov_y). Orthographic: parallel
// rays along forward from the plane through eye, half_height world units above and below the centre.
typedef struct {
  float eye[3];
  float tan_half_fov_y;  // perspective
  float right[3];  // unit
  float aspect;    // width / height
  float up[3];     // unit
  rc_int width;
  float forward[3];  // unit
  rc_int height;
  rc_int orthographic;  // 0: perspective, 1: orthographic
  float half_height;    // orthographic: half the view's height in world units (glTF's ymag)
  // Where in its pixel a camera ray passes (kernels/gbuffer.cl): through jitter_origin + jitter_cell * u, in pixels
  // from the pixel's top-left corner, with u = (0.5, 0.5) (the centre: origin 0, cell 1) or, for jitter_seed != 0, a
  // random point of the cell (path tracing over the pixel's area, one cell of an s x s grid a round).
  rc_uint jitter_seed;
  float jitter_cell;
  float jitter_origin[2];
  // Where this frame is the s-times larger frame of --pixel-samples s^2 (render/pixel_samples.h), s; else 0 or 1.
  // Without jitter, sub-pixel (i, j) of an output pixel then takes u on a rotated grid (kernels/gbuffer.cl).
  rc_int sub_pixel_side;
  float pad;
} CameraParams;

// The G-buffer: what the primary ray through each pixel's centre sees.
typedef struct {
  float position[3];
  rc_int triangle;  // -1 where the ray missed
  float normal[3];  // shading normal, facing the camera
  rc_int material;
  float geometric_normal[3];  // facing the camera
  float depth;                // distance along the primary ray
  float albedo[3];    // base colour (textured, times vertex colour)
  float metallic;     // at the pixel (texture times factor); 0 for Lambertian surfaces
  float emission[3];  // radiance emitted toward the camera
  float roughness;    // at the pixel
  float specular;     // the material's specular layer weight
  rc_int lobe;        // LOBE_* at the pixel
  // With normal maps (HAS_NORMAL_MAPS), the mapped shading normal, octahedral-encoded (kernels/surface.h); `normal`
  // stays the interpolated one, which the cache's weights and records use. NO_MAPPED_NORMAL in [0]: the pixel's
  // surface has no normal map, and `normal` shades.
  float mapped_normal[2];
} GBufferSample;
#define NO_MAPPED_NORMAL 2.0f

// One output pixel's surface layers (kernels/layers.cl) from its s x s sub-pixels (1 x 1 without anti-aliasing):
// emission, direct light, albedo and normal are means; position, depth and triangle the centre sub-pixel's (a single
// surface, device coordinates); the counts sums, so the host reads output-resolution layers only.
typedef struct {
  float emission[3];
  float shadow_rays;  // the sub-pixels' shadow rays together
  float direct[3];
  rc_int triangle;  // the centre sub-pixel's, -1 where its ray missed
  float albedo[3];
  float depth;
  float normal[3];
  rc_uint pad;
  float position[3];
  // Sub-pixels with geometry by how the cache shades their lobe: 8 bits each (s^2 <= 64), LOBE_ROUGH in the lowest,
  // then LOBE_GLOSSY, then LOBE_HSH (lobe_count_shift, lobe_count).
  rc_uint lobe_counts;
} PixelSurface;

// Placement lists its candidates in tiles of this many grid cells a side (kernels/placement.cl candidate_cell).
#define CANDIDATE_TILE 8

// The device's exclusive scan (kernels/scan.cl): SCAN_GROUP items a work-group, SCAN_ITEMS elements each.
#define SCAN_GROUP 256
#define SCAN_ITEMS 4
#define SCAN_BLOCK (SCAN_GROUP * SCAN_ITEMS)

// The work-group of the grids' lowest and highest corners (kernels/grid_sort.cl extreme_positions): each reduces this
// many items.
#define LOWEST_GROUP 256

// The work-group of the counts of a frame whose layers stay on the device (kernels/layers.cl count_lobes, sum_alpha,
// count_uncovered).
#define LAYER_COUNT_GROUP 256

// Where PixelSurface::lobe_counts keeps a lobe's count (8 bits each: side^2 <= 64); 32 for a lobe it does not count.
inline rc_uint lobe_count_shift(rc_int lobe) {
  return lobe == LOBE_ROUGH ? 0u : lobe == LOBE_GLOSSY ? 8u : lobe == LOBE_HSH ? 16u : 32u;
}
// The count of a lobe it counts (LOBE_ROUGH, LOBE_GLOSSY, LOBE_HSH).
inline rc_uint lobe_count(rc_uint lobe_counts, rc_int lobe) { return (lobe_counts >> lobe_count_shift(lobe)) & 0xffu; }

// A ray for the generic ray-casting kernel (tests, benchmarks) and its result.
typedef struct {
  float origin[3];
  float tmin;
  float direction[3];
  float tmax;
} RayDesc;

typedef struct {
  float t;  // tmax when nothing was hit
  float u, v;  // barycentrics of v1 and v2 (Embree's convention)
  rc_int prim;  // -1 when nothing was hit
} HitDesc;

// A ray that shading queued rather than traced where it asked for it (the wavefront trace: kernels/ray_queue.h): one
// kernel traces the queue, and the shading that asked, launched again, reads the answer from its slot. The answer is a
// HitDesc: the closest hit (prim -1: none), or for a shadow ray prim 0 where something blocks it, -1 where nothing does.
typedef struct {
  float origin[3];
  float tmax;          // 1 for a ray toward a point (direction = the point - origin), else INFINITY
  float direction[3];  // as the asker passed it to ray_precompute (not normalised for a ray toward a point)
  rc_uint slot;        // where its answer goes, with QUEUED_RAY_CLOSEST set for a closest-hit ray
} QueuedRay;
#define QUEUED_RAY_CLOSEST 0x80000000u
#define RAY_UNANSWERED (-3)  // a slot's prim before its ray is traced
// A shading round's mode (kernels/ray_queue.h): every ray traced where asked for; rays without an answer queued;
// every answer read, and what was shaded written.
#define RAYS_TRACED 0u
#define RAYS_QUEUED 1u
#define RAYS_ANSWERED 2u

// A record ray's path after its first hit, queued for the wavefront trace (kernels/path_queue.h): one bounce kernel a
// step over the queue, so no kernel holds a path's loop. The hit it stands on is kept as the trace gave it (hit_surface
// builds the same surface from it again).
typedef struct {
  rc_uint sample;         // where its (radiance, distance) waits in the samples buffer
  rc_uint launch_sample;  // its place in the launch (the rays it cast)
  rc_uint key, stream_sample;  // its random stream (PathContinuation)
  rc_uint mode;           // PATH_CONTINUES or PATH_STEPS_THEN_GATHERS; PATH_ENDED once it stops
  rc_uint rays;           // rays cast so far, its first hit's own included
  rc_int prim;            // the hit it stands on: triangle and barycentrics
  float u, v;
  float dir[3];           // the direction it reached that hit along
  float throughput[3];
  float sum[3];           // the light its bounces gathered so far
  float weight;           // the sample's factor (record_sample)
} QueuedPath;

#define RECORD_HORIZON_SECTORS 8
// An irradiance cache record (docs/ALGORITHM.md section 2): where it sits, how far it reaches, its irradiance and the
// Ward-Heckbert gradients. A gradient row is d(E.rgb)/d(axis): E_k(P) = E + sum_axis delta[axis] * row[axis].
typedef struct {
  float position[3];
  float radius;  // validity radius R in world units, clamped in screen space and by its neighbours
  float normal[3];
  rc_int pixel;  // the pixel it was placed at (index y * width + x)
  float irradiance[3];
  float pixel_size;  // world size of one pixel at the record, for the screen-space clamps
  float grad_translation[9];
  float grad_rotation[9];
  float harmonic_distance;  // Ward's harmonic mean hit distance, before any clamp
  // The strata's estimate of E's relative standard error (luminance; kernels/records.cl): where adaptive rays are on,
  // a record above the threshold is traced again with the full hemisphere.
  float relative_error;
  // Per azimuth sector of the record's tangent plane (kernels/cache_math.h horizon_sector): the distance beyond which
  // its low rays found an occluder (a wall it stands beside): points farther in that direction are hidden from it.
  float horizon[RECORD_HORIZON_SECTORS];
} CacheRecord;

// The largest hemisphere offered: M x N strata per record (theta x phi).
#define HEMISPHERE_MAX_THETA_STRATA 64
#define HEMISPHERE_MAX_PHI_STRATA 4096

// How records sample their hemisphere and clamp their radii.
typedef struct {
  rc_uint theta_strata;  // M, 1 .. HEMISPHERE_MAX_THETA_STRATA
  rc_uint phi_strata;    // N, 1 .. HEMISPHERE_MAX_PHI_STRATA
  rc_uint seed;
  float min_radius_pixels;  // clamps of the radius R, in pixel footprints at the record (the settings' clamps of the
  float max_radius_pixels;  // reach a R, divided by a)
  rc_uint guide_rays;       // rays aimed at the light guide's clusters, beside the M x N strata (0: none)
  rc_uint guide_clusters;   // clusters in the guide, 0 .. GUIDE_MAX_CLUSTERS
  rc_uint bounces;          // indirect bounces each ray gathers (kernels/bounce.h; 0 counts as 1)
  // The radius rule: 0 for Ward's harmonic mean distance; otherwise the occlusion Hessian's error budget C, the
  // radius then (C / lambda)^(1/4) pixel footprints for the relative irradiance's largest curvature lambda per pixel^2
  // (kernels/record_hessian.h). Either is clamped to [min, max].
  float hessian_error;
} HemisphereParams;

// The light guide (kernels/light_guide.cl, kernels/light_guide.h): where the scene's directly lit surfaces send the
// most light back, as a few bounding spheres, so that records aim rays at a small bright patch their strata would
// mostly miss.
#define GUIDE_MAX_CLUSTERS 32
#define GUIDE_MAX_STRATA 64.0f  // a record aims at a cluster only if it covers at most this many strata' solid angle
#define GUIDE_MIN_SHARE 0.01f  // and promises at least this share of the irradiance all clusters promise
#define GUIDE_MAX_CONES 8       // and is among the 8 that promise most (every stratum ray tests each cone)
// The guide's clusters are made from photons binned on a grid of GUIDE_GRID_CELLS cells per axis over the device
// frame's [-1, 1]^3 (a cell is 1/32 of the scene's diameter); a cell coordinate runs from -1 to GUIDE_GRID_CELLS (the
// photons outside clamped onto the rim), and each cell holds six bins, one per facing (host/cache/light_guide.cpp,
// kernels/guide_clusters.cl).
#define GUIDE_GRID_CELLS 32
#define GUIDE_CELL_SPAN (GUIDE_GRID_CELLS + 2)
#define GUIDE_BIN_COUNT (GUIDE_CELL_SPAN * GUIDE_CELL_SPAN * GUIDE_CELL_SPAN * 6)
// A region's sums, doubles at region * GUIDE_REGION_DOUBLES: flux (3), weighted position (3, then the centroid),
// weighted normal (3), weight, the weighted squared distances from the centroid.
#define GUIDE_REGION_DOUBLES 11
typedef struct {
  float centre[3];
  float radius;   // bounding sphere of the cluster's photon hits
  float flux[3];  // reflected flux (photon power x albedo), RGB
  float pad0;
  float normal[3];  // mean surface normal on the lit side (zero when the hits face every way)
  float pad1;
} GuideCluster;

// One landing of a photon from a light.
typedef struct {
  float position[3];
  rc_int hit;      // 0: the photon left the scene
  float normal[3]; // geometric normal on the side the photon came from
  rc_int landing;  // 0: the first surface from the light; k: after k reflections
  // Reflected flux: the arriving flux times the surface's albedo (base colour), the measure of a bright place that the
  // light guide clusters and the bounce probe sums.
  float flux[3];
  float pad1;
  // The flux arriving: the photon map's estimates are of irradiance, which a lookup turns into radiance by the
  // reflectance of the surface it looks from, toward its ray (kernels/photon_map.h).
  float incident[3];
  float pad2;
} PhotonHit;

// A small piece of the scene's surface on one side, for the photon map's estimates to measure the area of facing
// surface in a disc (host/cache/photon_map.h surface_patches).
typedef struct {
  float position[3];  // the piece's centroid
  float area;
  float normal[3];  // the side's normal
  float pad;
} SurfacePatch;

typedef struct {
  rc_uint photon_count;
  rc_uint source_count;  // punctual lights first, then emissive triangles, as in the sources' CDF
  rc_uint seed;
  rc_uint landings;  // surfaces each photon lands on at most (1: the first only)
  // Landings before this one are not stored: landing k of photon i at photons[i * (landings - first_stored) + k -
  // first_stored] (the photon map keeps the landings after a reflection, the light guide the first).
  rc_uint first_stored;
  // 1: the last source is the environment's smooth part, a sky (the bounce probe only, host/render/bounce_choice.cpp:
  // the light guide and the photon map gather a sky's smooth light and never shoot it).
  rc_uint sky_source;
  // 1: the caustic map's photons (kernels/caustic_map.cl): landing 0 reflects a photon only where the surface's lobe
  // is sharp (LOBE_GLOSSY), and only by that lobe, so that landing 1 holds exactly the light -> glossy -> surface paths
  // the records leave out (kernels/bounce.h hit_direct_without_caustics).
  rc_uint caustic;
  // Above 0: the glass caustic map's photons (HAS_GLASS_CAUSTICS, kernels/glass_caustics.cl), aimed at this many
  // bounding spheres of the glass volumes; a landing is kept only where the photon's way to it crossed or reflected
  // off a glass volume (landings 1, first_stored 0).
  rc_uint glass_caustics;
} PhotonParams;

// The photon map (--bounce-method photons; kernels/photon_map.h): photon landings after at least one reflection, sorted
// by a hashed grid of cubes of side cell_size >= radius, photons[cell_starts[h] .. cell_starts[h + 1]) in bucket h.
typedef struct {
  float grid_origin[3];
  float cell_size;
  float radius;          // of the density estimate around each photon
  rc_uint bucket_count;  // a power of two
  rc_uint photon_count;
  // A record ray that lands closer than this (device units) continues its path one bounce and reads the map there
  // (0: every ray reads it where it lands): the map's estimate averages a disc of `radius`, which at a short ray's end
  // spans the record's own neighbourhood, its contacts and recesses (--short-ray-paths, in radii).
  float short_path_distance;
  // A lookup whose photon's estimate summed fewer photons than this (in its disc, all landings) is where few photons
  // reach: its ray continues its path instead of reading the map (0: every lookup that finds a photon reads it).
  float min_support;
  rc_uint pad[3];
} PhotonMapParams;

// The glass caustic map (kernels/glass_caustics.cl) in levels of radius, each a grid of its own (PhotonMapParams, with
// its photons from first_photon and its buckets' starts from first_bucket of the map's arrays): a photon joins the
// level of the smallest radius r0 2^j about it that holds the map's neighbour count, so that its light spreads little
// where photons crowd (a focus) and far where they are few (a caustic's faint fringe), its flux whole either way.
#define GLASS_CAUSTIC_LEVELS 8
typedef struct {
  PhotonMapParams grid;
  rc_uint first_photon;
  rc_uint first_bucket;
  rc_uint pad[2];
  // Where the level's light can be: its photons' bounds widened by its radius (w unused). A point outside reads
  // nothing from the level, so most of the scene pays no lookup at all.
  float reach_min[4];
  float reach_max[4];
} CausticMapLevel;

// Kernel parameters. Every kernel takes its buffers by name and its other parameters in one of these structs
// (host/cl/named_kernel.h checks names and types against the compiled kernels).

// The counts the shading kernels loop over; the scene's arrays travel as SCENE_ARGS buffers (kernels/scene_args.h).
typedef struct {
  rc_uint light_count;    // punctual lights
  rc_uint emitter_count;  // emissive triangles
  // The environment map (kernels/environment.h; 0 x 0 without one) and its rotation about +Y (cos, sin).
  rc_uint environment_width, environment_height;
  float environment_rotation[2];
  // The peak's sampling normalisation: the sum over texels of the peak's luminance times the texel's solid angle
  // (0: no peak; all of the environment is gathered by escaping rays).
  float environment_peak_power;
  rc_uint pad;
} SceneCounts;

typedef struct {
  rc_uint strata_per_axis;  // light samples per pixel = strata_per_axis^2, stratified over the emitters
  rc_uint seed;
  // In rounds (kernels/direct.cl direct_light_round): samples [first_sample, first_sample + round_samples) of each
  // sub-pixel of the round's output pixels, listed (1) or all (0).
  rc_uint first_sample;
  rc_uint round_samples;
  rc_uint listed;
  rc_uint pad[3];
} DirectParams;

typedef struct {
  rc_uint first_sample;  // this launch adds samples first_sample .. first_sample + sample_count - 1
  rc_uint sample_count;
  rc_uint grid_side;  // stratified: samples drawn from a grid_side x grid_side grid over the hemisphere; 0: plain
  rc_uint seed;
  rc_uint bounces;    // indirect bounces per path (kernels/bounce.h; 0 counts as 1)
  rc_uint pad[3];
} PathParams;

// The lit surfaces camera rays see mirrored in glass (kernels/glass_mirror.cl).
typedef struct {
  rc_uint pixel_count;
  rc_uint samples;  // paths per pixel that looks at glass
  rc_uint seed;
  rc_uint bounces;  // the frame's indirect bounces: the mirrored surface's light has as many as a surface seen directly
} GlassMirrorParams;

// The splat's records found by position in the world (kernels/world_records.h; host/cache/world_record_grid.h): a
// hashed grid (kernels/photon_grid.h's hash) of cubes of side cell_size, bucket h listing, once each, the records
// whose reach (a sphere of accuracy x radius about the record: beyond it Ward's weight is below 1/a) meets a cell
// hashed to h: lists[starts[h] .. starts[h + 1]).
typedef struct {
  float grid_origin[3];
  float cell_size;
  rc_uint bucket_count;
  rc_uint record_count;    // 0: no index; every lookup finds no record
  float accuracy;          // the splat's a
  float irradiance_scale;  // the splat's bound on a record's extrapolated irradiance (fixed_point_irradiance_scale)
} WorldRecordParams;

// What the device's world-record grid build (kernels/world_record_grid.cl) gathers from the records before it lays
// out the grid: the lowest corner of their reach spheres, the widest and the median sphere, the brightest record.
typedef struct {
  rc_uint lowest[3];      // the lowest corner, each coordinate as ordered bits (a float's order as a uint's)
  rc_uint widest_bits;    // the widest reach sphere's diameter (a positive float's bits order as uints)
  rc_uint largest_bits;   // the largest irradiance component of any record
  rc_uint kept;           // records with a finite, positive reach and a finite position
  rc_uint median_bits;    // the median diameter (the kept / 2-th smallest), found a byte at a time from the top
  rc_uint median_rank;    // its rank among the diameters that share the bytes found so far
} WorldRecordExtent;

// Bins of one byte of the median's radix selection.
#define WORLD_RECORD_DIGIT_BINS 256

// The glossy pass's constants for one round of its samples (kernels/glossy.cl). A sampled sub-pixel's samples come in
// chunks of GLOSSY_CHUNK_LOBE lobe samples (and, with a light guide, GLOSSY_CHUNK_GUIDED aimed at it), each chunk an
// estimate of its own; a round adds chunks [first_chunk, first_chunk + round_chunks) to the sub-pixels of its output
// pixels (passes/glossy_pass.h).
#define GLOSSY_CHUNK_LOBE 2u
#define GLOSSY_CHUNK_GUIDED 1u
typedef struct {
  rc_uint first_chunk;   // 0: the first round, which writes every sub-pixel; later rounds add to theirs
  rc_uint round_chunks;  // chunks each sampled sub-pixel takes in this round
  rc_uint seed;
  rc_uint guide_clusters;  // the light guide's clusters (0: the lobe's samples alone)
  // Radiance caching with a light guide: the radiance records' strata (M N) and guided rays per record (n_g), whose
  // balance-heuristic share the records leave to each pixel, and the pixel's samples of it (0: none; first round).
  rc_uint record_strata;
  rc_uint record_guide_rays;
  rc_uint guide_share_samples;
  rc_uint bounces;  // indirect bounces each sample gathers (kernels/bounce.h; 0 counts as 1)
  rc_uint listed;   // 1: the round's output pixels are listed (pixel_list); 0: every output pixel, in order
  rc_uint slots_per_sub_pixel;  // the wavefront's sample slots per sub-pixel of an output pixel
  rc_uint pad[2];
} GlossyParams;

// A material's BRDF parameters (kernels/brdf.h), for the BRDF's HSH table (kernels/brdf_table.cl).
typedef struct {
  float base_color[3];
  float metallic;
  float roughness;
  float specular;  // KHR_materials_specular's factor, 1 by default
  float pad[2];
} BrdfMaterial;

// The BRDF table's layout: per material, angle_count view angles (cos(theta_o) at the bin centres (i + 0.5) /
// angle_count), each projected by chunk_count work items of samples_per_chunk BRDF samples.
typedef struct {
  rc_uint material_count;
  rc_uint angle_count;
  rc_uint chunk_count;
  rc_uint samples_per_chunk;
  rc_uint order;  // HSH order n: n^2 coefficients a colour channel
  rc_uint seed;
  rc_uint pad[2];
} BrdfTableParams;

// Radiance records (kernels/hsh_records.cl): each holds, per coefficient k of order n and colour channel, five parts
// of n^2 RGB triples: the incident radiance's HSH coefficients lambda, their translational gradients along the
// record's tangent t and bitangent b (kernels/sampling.h tangent_frame), and D_x lambda, D_y lambda for the
// small-angle tilt (host/cache/hsh_rotation.h). Floats per record: HSH_RECORD_PARTS * 3 * n^2.
#define HSH_RECORD_PARTS 5
#define HSH_PART_COEFFICIENTS 0
#define HSH_PART_GRADIENT_T 1
#define HSH_PART_GRADIENT_B 2
#define HSH_PART_TILT_X 3
#define HSH_PART_TILT_Y 4
typedef struct {
  rc_uint first_record;  // the batch: records first_record .. first_record + record_count - 1
  rc_uint record_count;
  rc_uint order;         // n
  rc_uint theta_strata;  // the batch's M x N strata
  rc_uint phi_strata;
  rc_uint pad[3];
} HshRecordParams;

// The radiance splat's constants for one frame (kernels/radiance_splat.cl).
typedef struct {
  float accuracy;         // the radiance records' a, stricter than the irradiance cache's
  float radiance_scale;   // fixed-point unit of w * L_o (the largest stratum radiance: no lobe reflects more)
  rc_uint record_count;
  rc_uint order;
  rc_uint angle_count;    // the BRDF table's view angles
  rc_uint pad[3];
} RadianceSplatParams;

// A batch of records: candidates[0 .. candidate_count - 1] become records first_record and up. The record pass
// (kernels/records.cl) takes it in launches of launch_count candidates from first_candidate, each candidate's samples
// (its strata, then its guided rays) in the samples buffer from candidate samples_first_candidate on.
typedef struct {
  HemisphereParams hemisphere;
  rc_uint candidate_count;
  rc_uint first_record;
  rc_uint first_candidate;
  rc_uint launch_count;
  rc_uint samples_first_candidate;
  rc_uint samples_per_item;  // consecutive samples of one record each work-item of the trace takes (1 on a GPU)
  rc_uint pad;
} RecordBatchParams;

// One light-guide cone as a record's rays share it (kernels/light_guide.h GuideCone, stored).
typedef struct {
  float axis[3];
  float cos_max;
  float inv_solid_angle;
  float promise;
  float cdf;
  float pad;
} StoredGuideCone;

// The cones a record aims its guided rays at, found once per record for all its rays.
typedef struct {
  StoredGuideCone cones[GUIDE_MAX_CONES];
  rc_uint count;
  rc_uint pad[7];
} RecordGuideCones;

// Placement's kernels, each reading the fields it needs.
typedef struct {
  rc_uint first_record;  // the records a kernel visits: first_record .. first_record + record_count - 1
  rc_uint record_count;
  float accuracy;   // a
  rc_int spacing;   // the placement grid's spacing in pixels (for neighbour clamping, the finest searched so far)
  rc_uint first_new;  // neighbour clamping: records first_new and up are the newest batch
  rc_int clamp_older;  // neighbour clamping: older records may shrink too (first round of a level)
  float min_radius_pixels;  // the radius clamp's minimum, in pixel footprints at the record
  float max_radius_pixels;  // fitting kept records to a view: the radius clamp's maximum
  rc_int harmonic_radius;   // fitting kept records: a record's own radius is its harmonic distance (no Hessian)
} PlacementParams;

// The splat's constants for one frame.
typedef struct {
  float accuracy;          // a: a record reaches points with Ward weight above 1/a
  float irradiance_scale;  // fixed-point unit of w * E (from the largest record irradiance)
  rc_uint first_record;  // the splat adds records first_record .. first_record + record_count - 1
  rc_uint record_count;
} SplatParams;

typedef struct {
  rc_uint ray_count;
  rc_uint pad[3];
} RayCastParams;

#ifndef __OPENCL_VERSION__
static_assert(sizeof(Bvh8Node) == 224 && alignof(Bvh8Node) == 4);
static_assert(sizeof(TriangleBlock8) == 320 && alignof(TriangleBlock8) == 4);
static_assert(sizeof(TriangleShading) == 128);
static_assert(sizeof(Material) == 176);
static_assert(sizeof(SurfaceLayers) == 48);
static_assert(sizeof(TextureInfo) == 16);
static_assert(sizeof(PunctualLight) == 64);
static_assert(sizeof(EmissiveTriangle) == 64);
static_assert(sizeof(CameraParams) == 96);
static_assert(sizeof(GBufferSample) == 96);
static_assert(sizeof(PixelSurface) == 80);
static_assert(sizeof(RayDesc) == 32);
static_assert(sizeof(HitDesc) == 16);
static_assert(sizeof(QueuedRay) == 32);
static_assert(sizeof(QueuedPath) == 76 && alignof(QueuedPath) == 4);
static_assert(sizeof(CacheRecord) == 160 && alignof(CacheRecord) == 4);
static_assert(sizeof(HemisphereParams) == 36);
static_assert(sizeof(GuideCluster) == 48);
static_assert(sizeof(PhotonHit) == 64);
static_assert(sizeof(SurfacePatch) == 32);
static_assert(sizeof(PhotonParams) == 32);
static_assert(sizeof(PhotonMapParams) == 48);
static_assert(sizeof(CausticMapLevel) == 96);
static_assert(sizeof(WorldRecordParams) == 32);
static_assert(sizeof(WorldRecordExtent) == 32);
static_assert(sizeof(BrdfMaterial) == 32);
static_assert(sizeof(BrdfTableParams) == 32);
static_assert(sizeof(SceneCounts) == 32);
static_assert(sizeof(DirectParams) == 32);
static_assert(sizeof(PathParams) == 32);
static_assert(sizeof(GlassMirrorParams) == 16);
static_assert(sizeof(RecordBatchParams) == 64);
static_assert(sizeof(StoredGuideCone) == 32);
static_assert(sizeof(RecordGuideCones) == 32 * GUIDE_MAX_CONES + 32);
static_assert(sizeof(HshRecordParams) == 32);
static_assert(sizeof(GlossyParams) == 48);
static_assert(sizeof(RadianceSplatParams) == 32);
static_assert(sizeof(PlacementParams) == 36);
static_assert(sizeof(SplatParams) == 16);
static_assert(sizeof(RayCastParams) == 16);
#endif

#endif
