#include "passes/brdf_table_pass.h"

#include <algorithm>

#include "kernels/hsh.h"
#include "util/error.h"

namespace rcsplat {
void BrdfTablePass::build_ahead(GpuContext& gpu) { gpu.build_ahead(kProgram); }

float BrdfTable::coefficient(size_t material, int angle, int term, int k) const {
  size_t row = material * size_t(angle_count) + size_t(angle);
  return lobe[(row * 2 + size_t(term)) * size_t(order * order) + size_t(k)];
}

double BrdfTable::captured_energy(size_t material, int angle, int order_used) const {
  double sum = 0.0;
  int n = std::min(order_used, order);
  for (int k = 0; k < n * n; ++k) {
    double c = coefficient(material, angle, 0, k);
    sum += c * c;
  }
  double e = energy[material * size_t(angle_count) + size_t(angle)];
  return e > 0.0 ? sum / e : 1.0;
}

double BrdfTable::worst_captured_energy(size_t material, int order_used) const {
  double worst = 1.0;
  for (int a = angle_count > 1 ? 1 : 0; a < angle_count; ++a)
    worst = std::min(worst, captured_energy(material, a, order_used));
  return worst;
}

BrdfTablePass::BrdfTablePass(GpuContext& gpu) : gpu_(gpu), kernel_(gpu.kernel(kProgram, "project_brdf")) {}

BrdfTable BrdfTablePass::compute(const std::vector<BrdfMaterial>& materials, int order, int angle_count,
                                 unsigned samples, unsigned seed) {
  if (order < 1 || order > HSH_MAX_ORDER) throw Error("HSH order must be 1.." + std::to_string(HSH_MAX_ORDER));
  if (angle_count < 1 || samples < 1) throw Error("BRDF table: need at least one view angle and one sample");
  BrdfTable table;
  table.order = order;
  table.angle_count = angle_count;
  size_t n2 = size_t(order) * size_t(order), rows = materials.size() * size_t(angle_count);
  table.lobe.assign(rows * 2 * n2, 0.0f);
  table.energy.assign(rows, 0.0f);
  if (materials.empty()) return table;

  BrdfTableParams params{};
  params.material_count = cl_uint(materials.size());
  params.angle_count = cl_uint(angle_count);
  params.samples_per_chunk = std::min(samples, 1024u);
  params.chunk_count = (samples + params.samples_per_chunk - 1) / params.samples_per_chunk;
  params.order = cl_uint(order);
  params.seed = seed;
  size_t items = rows * params.chunk_count, stride = 2 * n2 + 1;
  cl::Buffer input = gpu_.upload(materials, CL_MEM_READ_ONLY, "specular albedo table");
  cl::Buffer partial = gpu_.buffer(CL_MEM_WRITE_ONLY, items * stride * sizeof(float), "lobe table partial sums");
  kernel_.set_buffer<BrdfMaterial>("materials", input).set("params", params).set_buffer<cl_float>("partial", partial);
  kernel_.launch(items, 16);
  gpu_.queue().finish();
  std::vector<float> sums = gpu_.download<float>(partial, items * stride);
  // Chunks are equal in size: their means average in a fixed order, the same bits on every run.
  for (size_t row = 0; row < rows; ++row) {
    std::vector<double> total(stride, 0.0);
    for (size_t chunk = 0; chunk < params.chunk_count; ++chunk)
      for (size_t i = 0; i < stride; ++i) total[i] += sums[(row * params.chunk_count + chunk) * stride + i];
    for (size_t i = 0; i < 2 * n2; ++i) table.lobe[row * 2 * n2 + i] = float(total[i] / params.chunk_count);
    table.energy[row] = float(total[2 * n2] / params.chunk_count);
  }
  return table;
}

}  // namespace rcsplat
