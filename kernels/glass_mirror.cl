// Lit surfaces that camera rays see mirrored in glass (docs/ALGORITHM.md section 12). The G-buffer looks through glass
// and adds what the first glass point mirrors of the sky and of emitters (kernels/gbuffer.cl); the light of the
// surfaces the mirrored ray meets is not known then. This pass traces that ray again, `samples` times a pixel, and
// adds R times the light the surface it lands on sends back (its direct light and the frame's bounces after it, by
// path continuation: kernels/bounce.h; direct light alone in a frame without indirect light) to the pixel's direct
// light, which is light the pixel samples itself. A mirrored ray that passes more glass goes on through it as every
// secondary ray does (kernels/glass.h).
#include "bounce.h"
#include "counter_random.h"

// mirrors: two float4 a pixel from the G-buffer: the mirrored ray's origin and R (0: the pixel sees no glass), then
// its direction.
__kernel void mirror_in_glass(SCENE_ARGS, __global const float4* mirrors, GlassMirrorParams params,
                              __global float4* direct_out) {
  const uint pixel = get_global_id(0);
  if (pixel >= params.pixel_count) return;
  const float4 from = mirrors[2 * pixel];
  const float reflectance = from.w;
  if (!(reflectance > 0.0f)) return;
  const float3 toward = mirrors[2 * pixel + 1].xyz;
  const uint key = hash_u32(pixel ^ hash_u32(params.seed ^ STREAM_GLASS_MIRROR));
  RayTally rays = traced_rays(0u);
  float3 sum = (float3)(0.0f);
  for (uint s = 0u; s < params.samples; ++s) {
    float3 dir = toward, through_glass;
    HitSurface h;
    float distance;
    // A ray that leaves the scene brings nothing here: the G-buffer counted the sky it sees.
    if (!trace_surface(SCENE, from.xyz, &dir, 0.0f, &h, &distance, &through_glass, &rays)) continue;
    const PathContinuation more = path_continuation(key, s, params.bounces + 1u);
    sum += through_glass * radiance_from_hit(SCENE, &h, dir, distance, random01(key, s, 0u), random01(key, s, 1u),
                                             random01(key, s, 2u), more, &rays);
  }
  const float3 mirrored = finite_or_zero(sum * (reflectance / (float)params.samples));
  direct_out[pixel] = (float4)(direct_out[pixel].xyz + mirrored, direct_out[pixel].w + (float)rays.cast);
}
