// The glass caustic map at the pixels (--light-through-glass caustics, HAS_GLASS_CAUSTICS; docs/ALGORITHM.md section
// 12). A glass volume stops shadow rays there (kernels/glass.h light_transmittance), and the light it passes reaches
// the surfaces behind it as photons (kernels/light_guide.cl, PhotonParams::glass_caustics): a light's own, so it joins
// each pixel's direct light, which the cache and the path tracer share. The same map lights every bounce's hits
// (kernels/bounce.h hit_direct, kernels/reflected_light.h direct_reflected), since it travels in SCENE_ARGS.
#include "caustic_map.h"
#include "scene_args.h"
#include "shading_normal.h"
#include "surface.h"
#if HAS_SPECULAR_BRDF
#include "brdf_frame.h"
#endif

// direct[i] += what G-buffer sample i reflects toward the camera of the map's irradiance there: albedo / pi of it, or
// with a lobe its diffuse part and a rough lobe's albedo (irradiance_reflected; a sharper lobe's highlight of light
// through glass is not simulated).
__kernel void add_glass_caustics(SCENE_ARGS, GBUFFER_ARGS, __global float4* direct) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  GBufferSample g = gbuffer[i];
  if (g.triangle < 0) return;
  // Over the camera's sample spacing there: a focus smaller than a pixel is taken by its area (kernels/caustic_map.h).
  const float3 p = vload3(0, g.position);
  const float footprint = primary_cone_width(camera, camera->orthographic ? 0.0f : distance(p, vload3(0, camera->eye)));
  const float3 e = caustic_levels_irradiance(GLASS_CAUSTIC_MAP, p, vload3(0, g.geometric_normal), footprint);
  if (!any_positive(e)) return;
  float3 l = vload3(0, g.albedo) * RC_INV_PI * e;
#if HAS_SPECULAR_BRDF
  if (g.lobe != LOBE_NONE) {
    ShadingFrame frame = shading_frame(gbuffer_shading_normal(g));
    BrdfInputs in = gbuffer_layered_brdf(g, pixel_layers(gbuffer_layers, i), frame.n);
    l = irradiance_reflected(in, g.lobe, view_local(frame, camera_view_direction(camera, p)), e);
  }
#endif
  direct[i] += (float4)(finite_or_zero(l), 0.0f);
}
