// The BRDF's local frame at a shading point and what a pixel's shading needs from it: the view direction from the
// camera, the BRDF inputs a G-buffer sample holds, and the specular lobe's directional albedo. No tracing here, so
// the splat's resolve kernel can include it without the traversal's floating-point pragmas.
#ifndef RCSPLAT_BRDF_FRAME_H
#define RCSPLAT_BRDF_FRAME_H
#include "brdf.h"
#include "sampling.h"
#include "shared_types.h"

// An orthonormal frame with the shading normal as +z, the BRDF's local frame.
typedef struct {
  float3 t, b, n;
} ShadingFrame;

inline ShadingFrame shading_frame(float3 n) {
  ShadingFrame f;
  f.n = n;
  tangent_frame(n, &f.t, &f.b);
  return f;
}

inline float3 to_local(ShadingFrame f, float3 v) { return (float3)(dot(v, f.t), dot(v, f.b), dot(v, f.n)); }
inline float3 to_world(ShadingFrame f, float3 v) { return v.x * f.t + v.y * f.b + v.z * f.n; }

// The view direction in the local frame. An interpolated normal can tilt past the viewer (the geometric normal still
// faces it): the view is then taken just above the horizon rather than losing the pixel's reflection.
inline float3 view_local(ShadingFrame f, float3 wo_world) {
  float3 wo = to_local(f, wo_world);
  if (wo.z < 1e-4f) wo = normalize((float3)(wo.x, wo.y, 1e-4f));
  return wo;
}

// The unit direction from p toward the camera that sees it.
inline float3 camera_view_direction(__global const CameraParams* cam, float3 p) {
  if (cam->orthographic) return -vload3(0, cam->forward);
  return normalize(vload3(0, cam->eye) - p);
}

// The BRDF at a G-buffer sample: its base alone.
inline BrdfInputs gbuffer_brdf(GBufferSample g) {
  return brdf_inputs(vload3(0, g.albedo), g.metallic, g.roughness, g.specular);
}

// The whole BRDF at a G-buffer sample: its base and, in scenes with layers, its layers (pixel_layers), in the frame
// of its shading normal n.
inline BrdfInputs gbuffer_layered_brdf(GBufferSample g, SurfaceLayers layers, float3 n) {
#if HAS_LAYERS
  return with_layers(gbuffer_brdf(g), layers, n);
#else
  return gbuffer_brdf(g);
#endif
}

#endif
