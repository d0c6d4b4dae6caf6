// The rays a wavefront shading kernel queues instead of tracing (kernels/ray_queue.h), with the kernel that traces
// them (kernels/ray_queue.cl) and their answers. A stage (the first hits' shading, or one bounce of the queued paths)
// runs as rounds of its shading kernel: each round but the last lists the rays it needs and this traces them, the
// last reads every answer and writes what it shaded. The record pass and the glossy pass each own one.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>

#include "cl/device_scene.h"
#include "cl/gpu_context.h"
#include "cl/named_kernel.h"
#include "kernels/shared_types.h"

namespace rcsplat {

class RayQueue {
 public:
  RayQueue(GpuContext& gpu, const DeviceScene& scene, const char* what);
  static void build_ahead(GpuContext& gpu, const DeviceScene& scene);

  // Slots a hit's shading takes: a shadow ray per punctual light, two rays for the emitters (a light sample and,
  // on a glossy lobe, a BRDF sample that finds an emitter), three for an environment (its peak, its smooth part and a
  // glossy lobe's escape), at most kMaxSlotsPerHit (rays beyond are traced where asked for).
  static unsigned slots_per_hit(const DeviceScene& scene);
  static constexpr unsigned kMaxSlotsPerHit = 8;

  // Room for `works` works of `slots_per_work` slots each (works * slots_per_work < 2^31). most_works: the most works
  // one launch may hold, so that growing never doubles the buffers past one launch.
  void reserve(size_t works, unsigned slots_per_work, size_t most_works);
  // One stage of `rounds` rounds (2: the rays are independent, as a hit's shadow rays; 3: a path's next surface,
  // then its shadow rays) over `works` works. launch(mode) binds the kernel's parameters before the queue's, then
  // bind(kernel, mode), and launches it.
  void run_stage(unsigned rounds, size_t works, const std::function<void(cl_uint mode)>& launch);
  // Rays that a last round found unanswered within their slots and traced itself, since the queue was made: none
  // unless a shading asks for a ray after a closest hit that its rounds did not foresee (tests; reads the device).
  uint32_t traced_late();
  // Sets RAY_QUEUE_ARGS: the queue, its length, the answers, the slots per work and the round's mode.
  NamedKernel& bind(NamedKernel& kernel, cl_uint mode) const;

 private:
  GpuContext& gpu_;
  const DeviceScene& scene_;
  const char* what_;
  NamedKernel trace_;
  cl::Buffer queue_, length_, answers_;
  size_t queue_capacity_ = 0, answers_capacity_ = 0;
  unsigned slots_per_work_ = 1;
};

}  // namespace rcsplat
