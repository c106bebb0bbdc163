// The base mesh's creases (.srm version 3, format/srm/README.md): one flag
// per base edge saying whether the surface is sharp along it
// (SemiRegularMesh::crease_edges), which the wavelet's rules follow
// (LiftingPlan::build). Both sides list the edges from the base triangles in
// their decoded order, so the chunk holds nothing but the flags, coded by the
// adaptive binary range coder in the context of the creases already known
// around the edge (crease_model.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/status.h"

namespace srcodec {

// `triangles`: the base mesh as the decoder has it (BaseMeshCode::triangles);
// `creases`: edges (a, b), a < b, sorted, unique, in its vertex ids. Refuses
// an edge that is not an edge of `triangles`. Never empty when `creases` is
// not.
StatusOr<std::vector<uint8_t>> encode_creases(const std::vector<std::array<int32_t, 3>>& triangles,
                                              const std::vector<std::array<int32_t, 2>>& creases);

// The creases of `triangles` (decoded, so every index is below
// `vertex_count`) from a whole chunk: (a, b), a < b, sorted. Safe on any
// bytes: a chunk that ends before its last flag or runs on after it is an
// error naming the creases.
StatusOr<std::vector<std::array<int32_t, 2>>> decode_creases(const std::vector<std::array<int32_t, 3>>& triangles,
                                                              int32_t vertex_count, const uint8_t* data,
                                                              size_t size);

}  // namespace srcodec
