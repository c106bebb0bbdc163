// Refinement flags (DESIGN.md codec/; the adaptivity of Kammoun, Payan,
// Antonini §III-B, Eqs. 4-5): one bit per triangle and level, saying whether
// it is split 1-to-4. The decoder rebuilds the hierarchy by replaying the
// flags level by level on TriangleHierarchy, whose split() adds the balance
// and red-green closure itself; the encoder replays the same way, so both
// number nodes and vertices identically.
//
// Why each flag is the triangle's FINAL split state (not only whether the
// remesher selected it): a triangle of level j that a finer level's balance
// split later is then split in pass j, so pass j + 1 never has to split a
// coarser triangle. After pass j the hierarchy holds exactly the final nodes
// of levels <= j + 1, whatever follows: decoding to level j + 1 sees the same
// vertices, in the same order, as decoding everything.
#pragma once

#include <cstdint>
#include <vector>

#include "format/status.h"
#include "format/semi_regular/hierarchy.h"

namespace srcodec {

// The original hierarchy re-grown on the decoder's base mesh, and the link
// between the two.
struct ReplayedHierarchy {
  TriangleHierarchy hierarchy;              // what the decoder will build
  std::vector<int32_t> to_original_vertex;  // per replayed vertex
  std::vector<std::vector<uint8_t>> flags;  // one coded chunk per level 0 .. levels - 1
};

// `base` must be `original`'s base triangles reordered and rotated as the base
// mesh coder returned them: base[f] is original base triangle
// base_to_original_triangle[f] with its corners mapped by
// base_to_original_vertex and rotated cyclically.
StatusOr<ReplayedHierarchy> encode_refinement(const TriangleHierarchy& original, int32_t levels,
                                              const std::vector<std::array<int32_t, 3>>& base,
                                              const std::vector<int32_t>& base_to_original_vertex,
                                              const std::vector<int32_t>& base_to_original_triangle);

// Replays one level's flags (chunk of level `level`) on `hierarchy`, which
// must hold every final node of levels <= level. Stops with an error, not an
// allocation, when the vertices would pass `max_vertices`.
Status decode_refinement_level(TriangleHierarchy& hierarchy, int32_t level, const uint8_t* data, size_t size,
                               size_t max_vertices);

}  // namespace srcodec
