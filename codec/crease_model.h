// What both sides of the crease coder share (codec/crease_coder.h): the order
// of the base edges and the context of each one's flag.
//
// Order: the triangles as the base mesh decodes them, each one's edges
// (v0, v1), (v1, v2), (v2, v0), each edge at its first appearance.
//
// Context: creases run in curves, so an edge whose end already has one crease
// is likely the curve going on, and one whose ends have none is almost never
// a crease. The context is the pair of crease counts known at the two ends
// (0, 1, 2 or more; unordered: 6 pairs) times whether one of the triangle's
// earlier edges is a crease (a curve turning at one of its corners). On
// fandisk's 19419 edges with its 716 detected creases this codes the flags in
// 266 bytes where one model takes 545 (docs/codec_design.md, "Creases").
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "format/status.h"

namespace srcodec::crease_detail {

constexpr int kCountStates = 3;  // creases known at an end: 0, 1, 2 or more
constexpr int kPairs = kCountStates * (kCountStates + 1) / 2;
constexpr int kContexts = kPairs * 2;

inline uint64_t edge_key(int32_t a, int32_t b) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

// Counts at the two ends (each 0..2) and whether the triangle has a crease
// among its edges before this one.
inline int context(int at_a, int at_b, bool in_triangle) {
  const int lo = std::min(at_a, at_b), hi = std::max(at_a, at_b);
  // Unordered pairs (lo <= hi) numbered 0..5: (0,0) (0,1) (0,2) (1,1) (1,2) (2,2).
  const int pair = lo * kCountStates - lo * (lo - 1) / 2 + (hi - lo);
  return pair * 2 + (in_triangle ? 1 : 0);
}

// Every edge of `triangles` (indices below `vertex_count`) in coding order:
// `flag_of(a, b, context, flag)` (a < b) sets the edge's flag, 0 or 1 (the
// encoder's from its creases, the decoder's from the stream); a Status other
// than ok stops the walk and is returned.
template <typename FlagOf>
Status walk_edges(const std::vector<std::array<int32_t, 3>>& triangles, int32_t vertex_count, FlagOf&& flag_of) {
  std::vector<uint8_t> creases_at(static_cast<size_t>(vertex_count), 0);  // saturating at 2
  std::unordered_map<uint64_t, uint8_t> flags;  // lookups only: its order never shows
  flags.reserve(triangles.size() * 3 / 2 + 3);
  for (const std::array<int32_t, 3>& t : triangles) {
    bool in_triangle = false;
    for (int k = 0; k < 3; ++k) {
      const int32_t a = std::min(t[k], t[(k + 1) % 3]), b = std::max(t[k], t[(k + 1) % 3]);
      const auto [it, first] = flags.emplace(edge_key(a, b), 0);
      if (first) {
        int flag = 0;
        SRCODEC_RETURN_IF_ERROR(flag_of(a, b, context(creases_at[a], creases_at[b], in_triangle), flag));
        it->second = static_cast<uint8_t>(flag);
        if (flag) {
          creases_at[a] = static_cast<uint8_t>(std::min(creases_at[a] + 1, kCountStates - 1));
          creases_at[b] = static_cast<uint8_t>(std::min(creases_at[b] + 1, kCountStates - 1));
        }
      }
      in_triangle = in_triangle || it->second != 0;
    }
  }
  return ok_status();
}

}  // namespace srcodec::crease_detail
