// Radiance records' hemispherical harmonics (kernels/hsh_records.cl): projects each batch's strata (RecordPass with
// store_strata) onto the basis with translational gradients, then the tilt derivatives for the splat. Owns the
// coefficient array (HSH_RECORD_PARTS * 3 * n^2 floats a record, indexed like the record array) and the derivative
// matrices on the device.
#pragma once
#include <cstdint>
#include <vector>

#include "cl/gpu_context.h"
#include "cl/named_kernel.h"
#include "kernels/shared_types.h"

namespace rcsplat {

// kernels/hsh_records.cl's column table for N columns: per column k and m = -(order - 1) .. order - 1 (slot
// m + order - 1), COLUMN_TERMS floats: the integral over the column of H^m's azimuthal factor, that of
// (cos phi, sin phi) times it, and (-sin phi_k, cos phi_k) times it at the column's first wall.
std::vector<float> hsh_column_table(int order, unsigned columns);

class HshRecordPass {
 public:
  HshRecordPass(GpuContext& gpu, int order);
  // Starts building its program (GpuContext::build_ahead) with the switches the constructor will ask for.
  static void build_ahead(GpuContext& gpu);
  // A new frame's records: the brightest stratum seen starts again from `largest_kept` (0 for a cache of the frame's
  // own; kept records' brightest for a walkthrough: render/kept_records.h).
  void begin_frame(float largest_kept = 0.0f);
  // Records 0 .. count - 1 get kept records' coefficients (floats_per_record() each, as download gives them).
  void load(const std::vector<float>& coefficients, uint32_t count);
  size_t floats_per_record() const;
  // After records 0 .. kept_radii.size() - 1 (loaded) are fitted to a view (kernels/placement.cl fit_kept_records):
  // the gradients of each whose radius grew past its kept radius bounded for the new one, as project bounds them.
  void bound_fitted_gradients(const cl::Buffer& records, const std::vector<float>& kept_radii);

  // Records first .. first + count - 1 from the strata of their batch (theta_strata x phi_strata each), their
  // gradients bounded by the records' radii (records: the record pass's buffer); blocks.
  void project(const cl::Buffer& strata, const cl::Buffer& records, uint32_t first, uint32_t count,
               unsigned theta_strata, unsigned phi_strata);
  const cl::Buffer& coefficients() const { return coefficients_; }
  int order() const { return order_; }
  float largest_radiance();  // the brightest stratum any record saw (a bound on what a lobe can reflect)
  // Record i's floats (HSH_RECORD_PARTS parts of n^2 RGB triples), for tests and the summary.
  std::vector<float> download(uint32_t first, uint32_t count);

 private:
  static constexpr const char* kProgram = "hsh_records.cl";  // its kernels' file
  void reserve(size_t records);

  GpuContext& gpu_;
  int order_;
  NamedKernel project_, tilt_, bound_fitted_;
  cl::Buffer coefficients_, tilt_x_, tilt_y_, largest_bits_, column_table_;
  size_t capacity_ = 0;
  unsigned table_columns_ = 0;  // the N column_table_ was made for
};

}  // namespace rcsplat
