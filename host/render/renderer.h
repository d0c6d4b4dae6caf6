// The render pipeline, pass after pass: BVH build and upload, primary visibility, direct light, then indirect light by
// radiance cache splatting (or the classic octree lookup, or path tracing), and composition.
#pragma once
#include "cl/gpu_context.h"
#include "render/frame.h"
#include "render/settings.h"
#include "scene/scene.h"

namespace rcsplat {

RenderedImage render(GpuContext& gpu, const Scene& scene, const RenderSettings& settings);
// One primary sample per pixel of the G-buffer's frame (render() calls it once, on the sub-pixel frame when
// settings.pixel_samples > 1, settings.sub_pixel_side times the image's size); returns the image's layers, gathered.
RenderedImage render_single_sample(GpuContext& gpu, const Scene& scene, const RenderSettings& settings);

}  // namespace rcsplat
