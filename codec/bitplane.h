// Embedded bit-plane coding of quantized wavelet coefficients over zerotrees
// (EZW / SPIHT style significance, refinement and descendant passes), one
// arithmetic-coded segment per (plane, level) so that a stream cut anywhere,
// or truncated to the coarse levels, still decodes. See bitplane.cpp.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/status.h"

namespace srcodec {

constexpr int kMaxContextClasses = 64;
constexpr int kMaxBitplane = 30;  // |q| < 2^31

// The coefficients as a forest. Node = one scalar coefficient. Nodes are
// sorted by level; a node's parent is an earlier node of a lower level.
struct CoefficientForest {
  std::vector<int32_t> parent;         // per node; -1 = root; else level[parent] < level[node]
  std::vector<uint8_t> level;          // per node, 1..255, non-decreasing with node index
  std::vector<uint8_t> context_class;  // per node, < kMaxContextClasses; own adaptive models
};

// Checks the invariants above; the message names the first offending node.
Status validate_forest(const CoefficientForest& forest);

struct BitplaneSegment {
  int plane;
  int level;
  std::vector<uint8_t> bytes;  // may be empty (nothing to code there)
};

struct BitplaneStream {
  int top_plane = -1;  // highest plane with a significant coefficient; -1: all zero
  // One segment per (plane, level) for planes top_plane..0 and levels
  // 1..max level of the forest, in stream order: plane-major (descending),
  // level-minor (ascending). Empty when top_plane is -1.
  std::vector<BitplaneSegment> segments;
};

// `q`: per node, coefficient quantized in units of the finest step
// (dead zone: q = sign * floor(|c| / step)). `raw_planes`: the segments of
// planes below it hold raw bits instead of arithmetic-coded symbols (see
// bitplane.cpp); 0 writes the layout of .srm version 1. Preconditions
// (asserted): validate_forest(forest).ok(), q.size() == nodes,
// q != INT32_MIN, 0 <= raw_planes <= kMaxBitplane + 1.
BitplaneStream encode_bitplanes(const CoefficientForest& forest, const std::vector<int32_t>& q, int raw_planes = 0);

struct BitplaneSegmentView {
  int plane;
  int level;
  const uint8_t* data;
  size_t size;
};

struct BitplaneDecodeStats {
  // Lowest plane p such that every segment of planes >= p (levels <= the
  // decoded max level) was decoded completely; top_plane + 1 if none, 0 when
  // everything was decoded (also for an all-zero stream).
  int last_complete_plane = 0;
  size_t symbols = 0;           // binary symbols decoded and kept
  size_t segments_decoded = 0;  // segments decoded completely
  bool complete = false;        // every expected segment was present and complete
  int stop_plane = -1;          // where decoding stopped when !complete
  int stop_level = -1;
};

// Decodes what `segments` allow. `segments`: the segments the caller has, in
// stream order, each (plane, level) at most once; segments of levels above
// `max_level` are ignored, a missing segment or one cut short ends decoding
// there (everything after it in stream order is ignored, as if cut).
//
// Returns per node, in quantizer units:
//   0                                   if the node was never found significant;
//   sign * (m + 2^lp / 2)               otherwise, where lp is the lowest plane
//                                       decoded for the node and m = |q| with
//                                       bits below lp cleared: the middle of the
//                                       interval [m, m + 2^lp) known to hold |c| / step.
// So a fully decoded node gives sign * (|q| + 0.5); |value| < 2^(top_plane + 1).
//
// Errors (kInvalidArgument / kParseError) for an invalid forest, top_plane
// outside -1..30, max_level < 0, segments out of order, duplicated, outside
// planes 0..top_plane or levels 1..max forest level, or with null data and
// non-zero size. Any bytes inside valid segments decode to some values.
//
// kAuto decodes the finest level on a second thread, one plane behind the
// coarser levels, when it is the forest's last level and large enough to pay
// for the thread (see bitplane.cpp); kSequential never does, kPipelined does
// whenever it can (for tests). All three give the same values and stats.
enum class BitplaneThreads { kAuto, kSequential, kPipelined };

// `raw_planes`: as the encoder's (an error outside 0..kMaxBitplane + 1).
// Raw bits count as symbols in the stats.
StatusOr<std::vector<double>> decode_bitplanes(const CoefficientForest& forest, int top_plane,
                                               const std::vector<BitplaneSegmentView>& segments, int max_level,
                                               BitplaneDecodeStats* stats = nullptr,
                                               BitplaneThreads threads = BitplaneThreads::kAuto, int raw_planes = 0);

}  // namespace srcodec
