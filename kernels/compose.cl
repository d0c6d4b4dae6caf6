// Composition, shared by every cache method: the pixel's indirect light from the cached irradiance E (its weight in
// A, 0 where no record reached), and the final colour = emission + direct + indirect.
// The direct light comes weighed by the glass the pixel looked through (kernels/gbuffer.cl); the indirect is weighed
// here. A Lambertian pixel reflects albedo / pi * E. With a specular lobe (HAS_SPECULAR_BRDF) the irradiance carries the
// diffuse base, (1 - metallic) (1 - E_d(n.v)) base / pi * E, exact because that part of the BRDF is constant over the
// incident directions; a rough lobe adds its directional albedo times E / pi (the incident light taken as uniform over
// the lobe: an approximation, docs/NOTES.md "Material kinds"), a glossy lobe the light sampled from it (glossy.cl)
// or, with RADIANCE_CACHED, a radiance-cached lobe (LOBE_HSH) the light its records reflect toward the pixel's view
// (radiance_splat.cl), plus, with a light guide, the guide's share sampled per pixel (glossy.cl guide_share).
#include "sampling.h"
#include "shading_normal.h"
#include "scene_args.h"
#if HAS_SPECULAR_BRDF
#include "brdf_frame.h"
#endif

__kernel void compose(GBUFFER_ARGS, __global const float4* irradiance, __global const float4* direct,
                      __global const float4* glossy, __global const float4* cached_lobes,
                      uint glossy_holds_guide_share, __global const float4* see_through,
                      __global float4* indirect_out, __global float4* color_out) {
  uint i = get_global_id(0);
  if (i >= (uint)(camera->width * camera->height)) return;
  GBufferSample g = gbuffer[i];
  float4 cached = irradiance[i];
  float3 e = cached.xyz;
  float3 indirect = vload3(0, g.albedo) * RC_INV_PI * e;
#if HAS_SPECULAR_BRDF
  if (g.triangle >= 0 && g.lobe != LOBE_NONE) {
    ShadingFrame frame = shading_frame(gbuffer_shading_normal(g));
    BrdfInputs in = gbuffer_layered_brdf(g, pixel_layers(gbuffer_layers, i), frame.n);
    float3 wo = view_local(frame, camera_view_direction(camera, vload3(0, g.position)));
    indirect = irradiance_reflected(in, g.lobe, wo, e);
    if (RADIANCE_CACHED && g.lobe == LOBE_HSH)
      indirect += cached_lobes[i].xyz + (glossy_holds_guide_share ? glossy[i].xyz : (float3)(0.0f));
    else if (g.lobe != LOBE_ROUGH) indirect += glossy[i].xyz;
    indirect = finite_or_zero(indirect);
  }
#endif
#if HAS_TRANSMISSION
  indirect *= see_through[i].xyz;  // what the glass the camera looked through kept (kernels/gbuffer.cl)
#endif
  indirect_out[i] = (float4)(indirect, cached.w > 0.0f ? 1.0f : 0.0f);
  color_out[i] = (float4)(finite_or_zero(vload3(0, g.emission) + direct[i].xyz + indirect), 1.0f);
}
