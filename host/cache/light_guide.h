// The light guide's clusters: photon hits (passes/light_guide_pass.h) binned on a grid over the device frame's unit
// sphere, split by which way the surface faces, and the brightest bins kept as bounding spheres with their reflected
// flux. Records aim part of their rays at them (kernels/light_guide.h).
#pragma once
#include <vector>

#include "kernels/shared_types.h"

namespace rcsplat {

// Cells per axis of the binning grid over [-1, 1]^3 (the device frame), as the device bins them.
constexpr int kGuideGridCells = GUIDE_GRID_CELLS;

// At most max_clusters clusters (and GUIDE_MAX_CLUSTERS), brightest first; none without a photon hit.
std::vector<GuideCluster> cluster_photons(const std::vector<PhotonHit>& photons, unsigned max_clusters);

}  // namespace rcsplat
