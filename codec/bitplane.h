// Embedded bit-plane coding of quantized wavelet coefficients over zerotrees
// (EZW / SPIHT style significance, refinement and descendant passes), one
// arithmetic-coded segment per (plane, level) so that a stream cut anywhere,
// or truncated to the coarse levels, still decodes. The scheme: bitplane_model.h.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <utility>
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
// bitplane_model.h); 0 writes the layout of .srm version 1. Preconditions
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
  // decode_bitplane_values' `coarse_done` was called, with the values returned.
  bool coarse_done_final = false;
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
// for the thread (see bitplane_decode.cpp); kSequential never does, kPipelined does
// whenever it can (for tests). All three give the same values and stats.
enum class BitplaneThreads { kAuto, kSequential, kPipelined };

// Decoded values read where the decoder keeps them, its own per-node state
// (6 bytes a node, where the values take 8): value(i) is the value of node i
// described above. For a caller that scales the values into its own array,
// which then needs no array of doubles in between.
class BitplaneValueView {
 public:
  BitplaneValueView(const uint32_t* magnitude, const int8_t* low_plane, const uint8_t* flags, size_t size)
      : magnitude_(magnitude), low_plane_(low_plane), flags_(flags), size_(size) {}

  size_t size() const { return size_; }
  double value(size_t i) const {
    // A node never found significant has magnitude 0 and low plane -1 (entry
    // 31 of the table: 0), so it gives 0 without a branch, which would be
    // mispredicted on every other node of a partly decoded level.
    const double v = magnitude_[i] + kHalfStep.at[static_cast<uint8_t>(low_plane_[i]) & 31];
    return (flags_[i] & kNegativeFlag) ? -v : v;
  }

  static constexpr uint8_t kNegativeFlag = 1;  // in flags

 private:
  // 2^(plane - 1), the middle of the unknown bits below the lowest decoded
  // plane; entries above kMaxBitplane are 0.
  static_assert(kMaxBitplane < 31, "entry 31 is the insignificant nodes'");
  struct HalfSteps {
    double at[32];
  };
  static constexpr HalfSteps kHalfStep = [] {
    HalfSteps t{};
    double h = 0.5;
    for (int p = 0; p <= kMaxBitplane; ++p, h *= 2.0) t.at[p] = h;
    return t;
  }();

  const uint32_t* magnitude_;  // known bits of |q|
  const int8_t* low_plane_;    // lowest plane decoded, -1: never significant
  const uint8_t* flags_;       // kNegativeFlag for a negative value
  size_t size_;
};

// What decode_bitplane_values returns: the state a BitplaneValueView reads.
class BitplaneValues {
 public:
  BitplaneValues() = default;
  BitplaneValues(std::vector<uint32_t> magnitude, std::vector<int8_t> low_plane, std::vector<uint8_t> flags)
      : magnitude_(std::move(magnitude)), low_plane_(std::move(low_plane)), flags_(std::move(flags)) {}

  size_t size() const { return magnitude_.size(); }
  BitplaneValueView view() const { return {magnitude_.data(), low_plane_.data(), flags_.data(), size()}; }
  // Every value(i), in node order.
  std::vector<double> values() const;

 private:
  std::vector<uint32_t> magnitude_;
  std::vector<int8_t> low_plane_;
  std::vector<uint8_t> flags_;
};

// Called by the pipelined decode (kAuto's or kPipelined's) on the calling
// thread once every level but the last is decoded, while the last may still
// be: `coarse` views the nodes of those levels (a prefix of the forest) with
// their final values, unless the decode then has to start again
// sequentially (corrupt input only; see bitplane_decode.cpp), which
// BitplaneDecodeStats::coarse_done_final tells. At most once per decode;
// never by the sequential decode.
using CoarseLevelsDone = std::function<void(const BitplaneValueView& coarse)>;

// `raw_planes`: as the encoder's (an error outside 0..kMaxBitplane + 1).
// Raw bits count as symbols in the stats.
StatusOr<BitplaneValues> decode_bitplane_values(const CoefficientForest& forest, int top_plane,
                                                const std::vector<BitplaneSegmentView>& segments, int max_level,
                                                BitplaneDecodeStats* stats = nullptr,
                                                BitplaneThreads threads = BitplaneThreads::kAuto,
                                                int raw_planes = 0, const CoarseLevelsDone& coarse_done = {});

// The same as a vector of values.
StatusOr<std::vector<double>> decode_bitplanes(const CoefficientForest& forest, int top_plane,
                                               const std::vector<BitplaneSegmentView>& segments, int max_level,
                                               BitplaneDecodeStats* stats = nullptr,
                                               BitplaneThreads threads = BitplaneThreads::kAuto, int raw_planes = 0);

}  // namespace srcodec
