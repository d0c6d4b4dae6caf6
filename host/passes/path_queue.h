// The queue of paths that go on after their first hit in a wavefront trace (GroupSizes::record_trace): each
// QueuedPath (kernels/path_queue.h) and the queue's length, which stays on the device. The record pass and the glossy
// pass each own one; a shading kernel fills it, a step kernel carries every path one bounce further per launch, and a
// finish kernel adds each path's light to its sample.
#pragma once
#include <cstddef>
#include <functional>

#include "cl/gpu_context.h"
#include "cl/named_kernel.h"
#include "kernels/shared_types.h"
#include "passes/ray_queue.h"

namespace rcsplat {

class PathQueue {
 public:
  PathQueue(GpuContext& gpu, const char* what);

  // Room for `paths` paths (at least one, so a kernel that queues none still binds a queue), growing by doubling up
  // to `most` (one launch's samples).
  void reserve(size_t paths, size_t most);
  // Empties the queue before the kernel that fills it.
  void clear();
  // Sets the kernel's "paths" and "path_count" (its next two parameters).
  NamedKernel& bind(NamedKernel& kernel) const;
  // Takes every queued path `later_bounces` bounces further: a stage of `rays` a bounce, three rounds of `step` over
  // `items` work-items (its next surface, that surface's shadow rays, then its light). Work-items past the queue's
  // length return at once: a read of the length would stall the queue each bounce. bind_inputs sets the parameters
  // before the path queue's (scene, maps, records).
  void step(NamedKernel& step, const std::function<void(NamedKernel&)>& bind_inputs, cl_uint later_bounces,
            size_t items, RayQueue& rays);

 private:
  GpuContext& gpu_;
  const char* what_;
  cl::Buffer paths_, length_;
  size_t capacity_ = 0;
};

}  // namespace rcsplat
