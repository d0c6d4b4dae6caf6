#include "passes/ray_queue.h"

#include <algorithm>
#include <string>

#include "util/error.h"

namespace rcsplat {

void RayQueue::build_ahead(GpuContext& gpu, const DeviceScene& scene) {
  gpu.build_ahead("ray_queue.cl", scene.defines());
}

RayQueue::RayQueue(GpuContext& gpu, const DeviceScene& scene, const char* what)
    : gpu_(gpu), scene_(scene), what_(what), trace_(gpu.kernel("ray_queue.cl", "trace_queued_rays", scene.defines())) {
  length_ = gpu_.upload(std::vector<cl_uint>{0, 0}, CL_MEM_READ_WRITE, what);
  reserve(1, 1, 1);
}

unsigned RayQueue::slots_per_hit(const DeviceScene& scene) {
  const size_t slots = scene.lights().size() + (scene.emitters().empty() ? 0 : 2) +
                       (scene.environment_present() ? 3 : 0);
  return unsigned(std::clamp<size_t>(slots, 1, kMaxSlotsPerHit));
}

void RayQueue::reserve(size_t works, unsigned slots_per_work, size_t most_works) {
  const size_t slots = std::max<size_t>(works, 1) * std::max(slots_per_work, 1u);
  if (slots >= (size_t(1) << 31))
    throw Error(std::string(what_) + ": " + std::to_string(slots) + " ray slots in one launch (at most 2^31 - 1)");
  slots_per_work_ = std::max(slots_per_work, 1u);
  const size_t most = std::max(std::max<size_t>(most_works, 1) * slots_per_work_, slots);
  gpu_.reserve<QueuedRay>(queue_, queue_capacity_, slots, what_, false, most);
  gpu_.reserve<HitDesc>(answers_, answers_capacity_, slots, what_, false, most);
}

uint32_t RayQueue::traced_late() {
  cl_uint late = 0;
  gpu_.queue().enqueueReadBuffer(length_, CL_TRUE, sizeof(cl_uint), sizeof(cl_uint), &late);
  return late;
}

NamedKernel& RayQueue::bind(NamedKernel& kernel, cl_uint mode) const {
  return kernel.set_buffer<QueuedRay>("ray_queue", queue_)
      .set_buffer<cl_uint>("ray_queue_length", length_)
      .set_buffer<HitDesc>("ray_answers", answers_)
      .set("ray_slots", cl_uint(slots_per_work_))
      .set("ray_mode", mode);
}

void RayQueue::run_stage(unsigned rounds, size_t works, const std::function<void(cl_uint mode)>& launch) {
  const size_t slots = works * slots_per_work_;
  const HitDesc unanswered{0.0f, 0.0f, 0.0f, RAY_UNANSWERED};
  gpu_.queue().enqueueFillBuffer(answers_, unanswered, 0, slots * sizeof(HitDesc));
  for (unsigned round = 1; round < rounds; ++round) {
    gpu_.queue().enqueueFillBuffer(length_, cl_uint(0), 0, sizeof(cl_uint));
    launch(RAYS_QUEUED);
    scene_.bind(trace_);
    trace_.set_buffer<QueuedRay>("queue", queue_)
        .set_buffer<cl_uint>("queue_length", length_)
        .set_buffer<HitDesc>("answers", answers_)
        .launch(slots, gpu_.groups().traversal);
  }
  launch(RAYS_ANSWERED);
}

}  // namespace rcsplat
