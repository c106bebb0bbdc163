// How the .srm codec lays a semi-regular hierarchy out for its coders, the
// same on both sides (codec/srm_codec.h): the coefficient forest, the
// quantizer steps and the base mesh's grid.
#pragma once

#include <cstdint>
#include <vector>

#include "codec/base_mesh_coder.h"
#include "codec/bitplane.h"
#include "format/semi_regular/hierarchy.h"
#include "format/srm/srm_file.h"

namespace srcodec {

// The coefficient forest of a hierarchy up to `levels`: three nodes (one per
// component) per base vertex (f = 0, the base residual), then per vertex of
// level 1, 2, ... in id order. The tree parent of a level-j vertex (j >= 2)
// is the endpoint of its parent edge with the higher level (the newer one,
// always of level j - 1), ties to the higher id; level-1 vertices are roots.
struct ForestLayout {
  CoefficientForest forest;
  std::vector<int32_t> vertex;   // per node / 3: the hierarchy vertex
  std::vector<int32_t> first_node;  // per hierarchy vertex: its x node, -1 when above `levels`
};
ForestLayout build_forest(const TriangleHierarchy& h, int levels);

// quant_step x scale(f, c) for every (f, c), at index 3f + c.
std::vector<double> step_table(const SrmHeader& h);

// The base positions' grid the header describes.
QuantizationGrid grid_of(const SrmHeader& h);

}  // namespace srcodec
