// The remesher's result and the wavelet stage's input: a base mesh refined
// by 1-to-4 splits (adaptively, closed conformingly), one position per vertex.
// The remesher itself (Kammoun, Payan, Antonini) is not built yet; this is
// the shape of its output that the later stages build on.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "format/mesh.h"

namespace srcodec {

struct SemiRegularMesh {
  TriangleMesh base;                             // level 0: sites picked on the input
  std::vector<Eigen::Vector3d> positions;        // every vertex of every level; base vertices first
  std::vector<uint8_t> level;                    // level at which each vertex appears
  std::vector<std::array<int32_t, 2>> parent_edge;  // endpoints of the edge a vertex splits; {-1,-1} for base
  std::vector<std::vector<std::array<int32_t, 3>>> level_triangles;  // the watertight mesh at each level
};

}  // namespace srcodec
