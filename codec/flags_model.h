// What both sides of the refinement-flag coder share (codec/flags_coder.h):
// the flags' contexts and the level-by-level replay that gives every leaf
// its flag in the same order on both sides.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

#include "format/semi_regular/hierarchy.h"
#include "format/status.h"

namespace srcodec::flags_detail {

constexpr int kContextLevels = 8;
constexpr int kContextsPerLevel = 5;  // level 0: the previous flag (0, 1); finer: split earlier siblings (0..3)

// Flags of triangles that share a parent are correlated (a region is refined
// or not), so the context is how many earlier siblings were split.
inline int flag_context(const TriangleHierarchy& h, int32_t node, int previous_flag) {
  const TriangleHierarchy::Node& n = h.nodes()[node];
  const int level = std::min<int>(n.level, kContextLevels - 1);
  if (n.parent < 0) return level * kContextsPerLevel + previous_flag;
  const int32_t first = h.nodes()[n.parent].first_child;
  int split = 0;
  for (int32_t s = first; s < node; ++s) split += h.nodes()[s].first_child >= 0;
  return level * kContextsPerLevel + split;
}

// One pass: every leaf of level `level`, in node order (the order grows as
// splits append nodes), gets a flag from `decide`; a node that closure split
// before its turn gets none. `after_split` runs after each split.
template <typename Decide, typename AfterSplit>
Status replay_level(TriangleHierarchy& h, int32_t level, size_t max_vertices, Decide&& decide,
                    AfterSplit&& after_split) {
  int previous = 0;
  for (size_t n = 0; n < h.nodes().size(); ++n) {
    const TriangleHierarchy::Node& node = h.nodes()[n];
    if (node.level != level || node.first_child >= 0) continue;
    const int32_t id = static_cast<int32_t>(n);
    int flag = 0;
    SRCODEC_RETURN_IF_ERROR(decide(id, flag_context(h, id, previous), flag));
    previous = flag;
    if (!flag) continue;
    h.split(id);
    if (static_cast<size_t>(h.vertex_count()) > max_vertices)
      return parse_error("level " + std::to_string(level + 1) + " would have more than " +
                         std::to_string(max_vertices) + " vertices");
    after_split();
  }
  return ok_status();
}

}  // namespace srcodec::flags_detail
