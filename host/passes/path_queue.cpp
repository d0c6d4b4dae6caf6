#include "passes/path_queue.h"

#include <algorithm>

namespace rcsplat {

PathQueue::PathQueue(GpuContext& gpu, const char* what) : gpu_(gpu), what_(what) {
  length_ = gpu_.upload(std::vector<cl_uint>{0}, CL_MEM_READ_WRITE, what);
  reserve(1, 1);
}

void PathQueue::reserve(size_t paths, size_t most) {
  gpu_.reserve(paths_, capacity_, std::max<size_t>(paths, 1), sizeof(QueuedPath), what_, false,
               std::max<size_t>(most, 1));
}

void PathQueue::clear() { gpu_.queue().enqueueFillBuffer(length_, cl_uint(0), 0, sizeof(cl_uint)); }

NamedKernel& PathQueue::bind(NamedKernel& kernel) const {
  return kernel.set_buffer<QueuedPath>("paths", paths_).set_buffer<cl_uint>("path_count", length_);
}

void PathQueue::step(NamedKernel& step, const std::function<void(NamedKernel&)>& bind_inputs, cl_uint later_bounces,
                     size_t items, RayQueue& rays) {
  for (cl_uint bounce = 0; bounce < later_bounces; ++bounce)
    rays.run_stage(3, items, [&](cl_uint mode) {
      bind_inputs(step);
      rays.bind(bind(step).set("bounce", bounce).set("later_bounces", later_bounces), mode)
          .launch(items, gpu_.groups().traversal);
    });
}

}  // namespace rcsplat
