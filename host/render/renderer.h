// The render pipeline, pass after pass: BVH build and upload, primary visibility, direct light, then indirect light by
// radiance cache splatting (or the classic octree lookup, or path tracing), and composition.
#pragma once
#include "cl/gpu_context.h"
#include "render/frame.h"
#include "render/settings.h"
#include "scene/scene.h"

namespace rcsplat {

RenderedImage render(GpuContext& gpu, const Scene& scene, const RenderSettings& settings);

}  // namespace rcsplat
