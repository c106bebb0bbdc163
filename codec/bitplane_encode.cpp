// The encoding half of the bit-plane coder (codec/bitplane.h): each node's
// symbols come from |q| and the largest magnitude among its descendants.
#include <algorithm>
#include <cassert>
#include <cstdint>
#include <vector>

#include "codec/bitplane.h"
#include "codec/bitplane_model.h"
#include "codec/range_coder.h"

namespace srcodec {

using namespace bitplane_detail;

namespace {

// Encoder side: the bits come from |q| and the descendants' maxima.
struct EncoderIo {
  const std::vector<uint32_t>& magnitude;
  const std::vector<uint32_t>& descendant_max;
  const std::vector<int32_t>& q;
  bool raw_plane;  // the symbols go to the raw bit lists (see the top)
  ArithmeticEncoder enc;
  std::vector<uint8_t> raw_refinement, raw_rest;  // one bit per entry

  int put(int bit, BitModel& m) {
    if (raw_plane) {
      raw_rest.push_back(static_cast<uint8_t>(bit));
    } else {
      enc.encode(bit, m);
    }
    return bit;
  }
  int significance(uint32_t n, int p, BitModel& m) { return put(static_cast<int>((magnitude[n] >> p) & 1u), m); }
  int refine(uint32_t n, int p, BitModel& m) {
    const int bit = static_cast<int>((magnitude[n] >> p) & 1u);
    if (!raw_plane) return put(bit, m);
    raw_refinement.push_back(static_cast<uint8_t>(bit));
    return bit;
  }
  // The segment's bytes.
  std::vector<uint8_t> finish() {
    if (!raw_plane) return enc.finish();
    std::vector<uint8_t> bytes((raw_refinement.size() + raw_rest.size() + 7) / 8, 0);
    size_t k = 0;
    for (const auto* list : {&raw_refinement, &raw_rest})
      for (uint8_t bit : *list) {
        bytes[k >> 3] = static_cast<uint8_t>(bytes[k >> 3] | (bit << (k & 7)));
        ++k;
      }
    return bytes;
  }
  int sign(uint32_t n, BitModel& m) { return put(q[n] < 0 ? 1 : 0, m); }
  int descendants(uint32_t n, int p, BitModel& m) { return put((descendant_max[n] >> p) != 0 ? 1 : 0, m); }
  bool ok() const { return true; }
};

uint32_t magnitude_of(int32_t v) {
  assert(v != INT32_MIN);
  const uint32_t m = v < 0 ? 0u - static_cast<uint32_t>(v) : static_cast<uint32_t>(v);
  return std::min<uint32_t>(m, (uint32_t{1} << (kMaxBitplane + 1)) - 1);
}

int top_bit(uint32_t x) { return x == 0 ? -1 : 31 - __builtin_clz(x); }

}  // namespace

BitplaneStream encode_bitplanes(const CoefficientForest& forest, const std::vector<int32_t>& q, int raw_planes) {
  assert(validate_forest(forest).ok());
  assert(raw_planes >= 0 && raw_planes <= kMaxBitplane + 1);
  assert(q.size() == forest.parent.size());
  const size_t n = forest.parent.size();
  std::vector<uint32_t> magnitude(n), descendant_max(n, 0);
  uint32_t all_max = 0;
  for (size_t i = 0; i < n; ++i) magnitude[i] = magnitude_of(q[i]);
  for (size_t i = n; i-- > 0;) {
    all_max = std::max(all_max, magnitude[i]);
    const int32_t p = forest.parent[i];
    if (p >= 0) {
      uint32_t& d = descendant_max[static_cast<size_t>(p)];
      d = std::max({d, magnitude[i], descendant_max[i]});
    }
  }
  BitplaneStream out;
  out.top_plane = top_bit(all_max);
  if (out.top_plane < 0) return out;

  const ForestIndex index = build_index(forest);
  CoderState state(forest, index, raw_planes);
  size_t symbols = 0;
  for (int p = out.top_plane; p >= 0; --p) {
    for (int l = 1; l <= index.max_level; ++l) {
      EncoderIo io{magnitude, descendant_max, q, p < raw_planes, {}, {}, {}};
      state.code_level(p, l, io, &symbols);
      out.segments.push_back({p, l, io.finish()});
    }
  }
  return out;
}

}  // namespace srcodec
