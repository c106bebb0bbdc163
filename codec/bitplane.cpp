// Embedded bit-plane coding over zerotrees: J. M. Shapiro, "Embedded image
// coding using zerotrees of wavelet coefficients" (IEEE TSP 41(12), 1993) and
// A. Said, W. A. Pearlman, "A new, fast, and efficient image codec based on set
// partitioning in hierarchical trees" (SPIHT, IEEE TCSVT 6(3), 1996), as used
// for meshes by A. Khodakovsky, P. Schröder, W. Sweldens, "Progressive
// geometry compression" (SIGGRAPH 2000).
//
// Per plane p (top..0) and level l (1..L) one segment, coded by its own
// ArithmeticEncoder; the adaptive models persist across planes, one set per
// (level, context class), so decoding levels <= L' never needs a later level.
// For each node n of level l that is REACHED (a root, or D(parent) is true),
// in index order, one atomic group of symbols:
//   significant before p:  refinement bit p of |q|;
//   else:                  significance |q| >= 2^p, then the sign if so;
//   then, if n has children and D(n) is still false:
//                          D(n) = some strict descendant has |q| >= 2^p.
// D(n) true makes n's children reached from then on (D(parent) is coded in
// the parent's segment, which precedes the child's in stream order).
//
// Contexts (all known to a decoder of levels <= l at that point), one model
// set per (level, context class):
//   significance: parent state {root, insignificant, significant at p, at
//                 p + 1, earlier} x {n coded at an earlier plane or newly reached};
//   sign:         parent's sign {none / insignificant, +, -};
//   refinement:   one model;
//   D:            n's own state {insignificant, significant at p, at p + 1,
//                 earlier} x {n coded at an earlier plane or newly reached}.
// On synthetic wavelet-like forests (tests/codec/bitplane_test.cpp, 1.5M
// nodes) the per-(level, class) split does most of the work; the significance
// and D contexts save a further 0.7%, refinement contexts (planes since
// significance) and finer parent buckets nothing measurable, so they are out.
// Signs there are independent and the parent-sign context costs 0.01%: kept
// for real meshes, where neighbouring detail vectors may agree in sign.
//
// Decoding checks ArithmeticDecoder::ok() after each group: a group that
// depended on bytes past the end of its segment is dropped and decoding stops
// there, so everything returned is exactly the encoder's knowledge.
#include "codec/bitplane.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "codec/range_coder.h"

namespace srcodec {
namespace {

constexpr int kSigContexts = 5 * 2;
constexpr int kDescContexts = 4 * 2;

struct ModelSet {
  BitModel sig[kSigContexts];
  BitModel sign[3];
  BitModel refine;
  BitModel desc[kDescContexts];
};

// Derived from a valid forest; shared by encoder and decoder.
struct ForestIndex {
  int max_level = 0;
  std::vector<uint32_t> level_begin;  // level l: nodes [level_begin[l], level_begin[l + 1])
  std::vector<uint32_t> child_begin;  // CSR over children, size nodes + 1
  std::vector<uint32_t> children;
  std::vector<uint16_t> model_set;    // per node: dense id of (level, context_class)
  size_t model_sets = 0;
};

ForestIndex build_index(const CoefficientForest& f) {
  ForestIndex x;
  const size_t n = f.parent.size();
  x.max_level = n == 0 ? 0 : f.level.back();
  x.level_begin.assign(static_cast<size_t>(x.max_level) + 2, static_cast<uint32_t>(n));
  for (size_t i = n; i-- > 0;) x.level_begin[f.level[i]] = static_cast<uint32_t>(i);
  for (int l = x.max_level; l >= 1; --l) x.level_begin[l] = std::min(x.level_begin[l], x.level_begin[l + 1]);
  x.level_begin[0] = 0;

  x.child_begin.assign(n + 1, 0);
  for (size_t i = 0; i < n; ++i)
    if (f.parent[i] >= 0) ++x.child_begin[static_cast<size_t>(f.parent[i]) + 1];
  for (size_t i = 0; i < n; ++i) x.child_begin[i + 1] += x.child_begin[i];
  x.children.resize(x.child_begin[n]);
  std::vector<uint32_t> fill(x.child_begin.begin(), x.child_begin.end() - 1);
  for (size_t i = 0; i < n; ++i)
    if (f.parent[i] >= 0) x.children[fill[static_cast<size_t>(f.parent[i])]++] = static_cast<uint32_t>(i);

  std::vector<int32_t> dense(256 * kMaxContextClasses, -1);
  x.model_set.resize(n);
  for (size_t i = 0; i < n; ++i) {
    int32_t& id = dense[f.level[i] * kMaxContextClasses + f.context_class[i]];
    if (id < 0) id = static_cast<int32_t>(x.model_sets++);
    x.model_set[i] = static_cast<uint16_t>(id);
  }
  return x;
}

enum NodeFlag : uint8_t { kNegative = 1, kDescendants = 2, kSeen = 4, kHasChildren = 8 };

// The state both sides keep: what the decoder knows after each group.
struct CoderState {
  const CoefficientForest& forest;
  const ForestIndex& index;
  std::vector<ModelSet> models;
  std::vector<uint8_t> flags;
  std::vector<int8_t> sig_plane;   // plane where the node became significant, -1: not yet
  std::vector<int8_t> low_plane;   // lowest plane decoded for a significant node
  std::vector<uint32_t> magnitude; // known bits of |q|
  std::vector<uint64_t> reached;   // bitset: roots, and children of nodes with D true

  CoderState(const CoefficientForest& f, const ForestIndex& x)
      : forest(f), index(x), models(x.model_sets), flags(f.parent.size(), 0), sig_plane(f.parent.size(), -1),
        low_plane(f.parent.size(), -1), magnitude(f.parent.size(), 0), reached((f.parent.size() + 63) / 64, 0) {
    for (size_t i = 0; i < f.parent.size(); ++i) {
      if (f.parent[i] < 0) reached[i >> 6] |= uint64_t{1} << (i & 63);
      if (x.child_begin[i] != x.child_begin[i + 1]) flags[i] = kHasChildren;
    }
  }

  int sig_context(uint32_t n, int p) const {
    const int32_t parent = forest.parent[n];
    int bucket = 0;
    if (parent >= 0) {
      const int sp = sig_plane[static_cast<size_t>(parent)];
      bucket = sp < 0 ? 1 : 2 + std::min(sp - p, 2);
    }
    return bucket * 2 + ((flags[n] & kSeen) ? 0 : 1);
  }
  int sign_context(uint32_t n) const {
    const int32_t parent = forest.parent[n];
    if (parent < 0 || sig_plane[static_cast<size_t>(parent)] < 0) return 0;
    return (flags[static_cast<size_t>(parent)] & kNegative) ? 2 : 1;
  }
  int desc_context(uint32_t n, int p, bool now_significant) const {
    const int sp = sig_plane[n];
    const int own = sp >= 0 ? 2 + std::min(sp - p - 1, 1) : (now_significant ? 1 : 0);
    return own * 2 + ((flags[n] & kSeen) ? 0 : 1);
  }

  // One node's group at plane p. Returns false (and changes nothing) if
  // io.ok() fails after the group. Adds the group's symbols to *symbols.
  template <class Io>
  bool code_node(uint32_t n, int p, Io& io, size_t* symbols) {
    ModelSet& m = models[index.model_set[n]];
    const int sp = sig_plane[n];
    int refine = 0, significant = 0, negative = 0, desc = 0, used = 1;
    if (sp >= 0) {
      refine = io.refine(n, p, m.refine);
    } else {
      significant = io.significance(n, p, m.sig[sig_context(n, p)]);
      if (significant) {
        negative = io.sign(n, m.sign[sign_context(n)]);
        ++used;
      }
    }
    const bool code_desc = (flags[n] & (kDescendants | kHasChildren)) == kHasChildren;
    if (code_desc) {
      desc = io.descendants(n, p, m.desc[desc_context(n, p, significant != 0)]);
      ++used;
    }
    if (!io.ok()) return false;
    *symbols += static_cast<size_t>(used);
    if (sp >= 0) {
      magnitude[n] |= static_cast<uint32_t>(refine) << p;
    } else if (significant) {
      sig_plane[n] = static_cast<int8_t>(p);
      magnitude[n] = uint32_t{1} << p;
      if (negative) flags[n] |= kNegative;
    }
    if (sp >= 0 || significant) low_plane[n] = static_cast<int8_t>(p);
    flags[n] |= kSeen;
    if (desc) {
      flags[n] |= kDescendants;
      for (uint32_t c = index.child_begin[n]; c < index.child_begin[n + 1]; ++c) {
        const uint32_t child = index.children[c];
        reached[child >> 6] |= uint64_t{1} << (child & 63);
      }
    }
    return true;
  }

  // Calls visit(n) for every reached node of `level` in index order (nodes
  // that visit() makes reached are of later levels); stops at the first
  // visit() that returns false and returns false then.
  template <class Visit>
  bool for_reached(int level, Visit&& visit) {
    const uint32_t begin = index.level_begin[level], end = index.level_begin[level + 1];
    if (begin >= end) return true;
    for (uint32_t w = begin >> 6; w <= (end - 1) >> 6; ++w) {
      uint64_t bits = reached[w];
      if (w == begin >> 6) bits &= ~uint64_t{0} << (begin & 63);
      if (w == (end - 1) >> 6 && (end & 63) != 0) bits &= ~(~uint64_t{0} << (end & 63));
      while (bits != 0) {
        const uint32_t n = (w << 6) | static_cast<uint32_t>(__builtin_ctzll(bits));
        bits &= bits - 1;
        if (!visit(n)) return false;
      }
    }
    return true;
  }

  // Codes every reached node of `level` at plane p, in index order. Returns
  // false at the first group that io could not complete.
  template <class Io>
  bool code_level(int p, int level, Io& io, size_t* symbols) {
    return for_reached(level, [&](uint32_t n) { return code_node(n, p, io, symbols); });
  }
};

// Encoder side: the bits come from |q| and the descendants' maxima.
struct EncoderIo {
  const std::vector<uint32_t>& magnitude;
  const std::vector<uint32_t>& descendant_max;
  const std::vector<int32_t>& q;
  ArithmeticEncoder enc;

  int put(int bit, BitModel& m) {
    enc.encode(bit, m);
    return bit;
  }
  int significance(uint32_t n, int p, BitModel& m) { return put(static_cast<int>((magnitude[n] >> p) & 1u), m); }
  int refine(uint32_t n, int p, BitModel& m) { return put(static_cast<int>((magnitude[n] >> p) & 1u), m); }
  int sign(uint32_t n, BitModel& m) { return put(q[n] < 0 ? 1 : 0, m); }
  int descendants(uint32_t n, int p, BitModel& m) { return put((descendant_max[n] >> p) != 0 ? 1 : 0, m); }
  bool ok() const { return true; }
};

struct DecoderIo {
  ArithmeticDecoder& dec;

  int significance(uint32_t, int, BitModel& m) { return dec.decode(m); }
  int refine(uint32_t, int, BitModel& m) { return dec.decode(m); }
  int sign(uint32_t, BitModel& m) { return dec.decode(m); }
  int descendants(uint32_t, int, BitModel& m) { return dec.decode(m); }
  bool ok() const { return dec.ok(); }
};

// Decodes every reached node of `level` at plane p from `dec`: CoderState::
// code_node's group, written out on a register-held decoder (Cursor) while a
// whole group's bytes are there (none of its symbols can then depend on
// missing bytes), and code_node itself, with its checks, near the end.
// kLeaves: no node of the level has children (the finest level, most of the
// nodes), so no group has a D symbol: a shorter loop that keeps more in registers.
template <bool kLeaves>
bool decode_level(CoderState& state, int p, int level, ArithmeticDecoder& dec, size_t* symbols) {
  constexpr size_t kGroupSymbols = 3;
  const int32_t* const parent = state.forest.parent.data();
  const uint16_t* const model_set = state.index.model_set.data();
  const uint32_t* const child_begin = state.index.child_begin.data();
  const uint32_t* const children = state.index.children.data();
  ModelSet* const models = state.models.data();
  uint8_t* const flags = state.flags.data();
  int8_t* const sig_plane = state.sig_plane.data();
  int8_t* const low_plane = state.low_plane.data();
  uint32_t* const magnitude = state.magnitude.data();
  uint64_t* const reached = state.reached.data();
  const int8_t plane = static_cast<int8_t>(p);
  const uint32_t plane_bit = uint32_t{1} << p;

  const uint32_t begin = state.index.level_begin[level], end = state.index.level_begin[level + 1];
  if (begin >= end) return true;
  ArithmeticDecoder::Cursor rc(dec);
  size_t count = 0;
  uint32_t w = begin >> 6;
  uint64_t bits = 0;
  bool fast = true;
  // Next reached node of the level, or `end`.
  const auto next_node = [&]() -> uint32_t {
    while (bits == 0) {
      if (++w > (end - 1) >> 6) return end;
      bits = reached[w];
      if (w == (end - 1) >> 6 && (end & 63) != 0) bits &= ~(~uint64_t{0} << (end & 63));
    }
    const uint32_t n = (w << 6) | static_cast<uint32_t>(__builtin_ctzll(bits));
    bits &= bits - 1;
    return n;
  };
  bits = reached[w] & (~uint64_t{0} << (begin & 63));
  if (w == (end - 1) >> 6 && (end & 63) != 0) bits &= ~(~uint64_t{0} << (end & 63));
  uint32_t n = next_node();
  for (; n != end; n = next_node()) {
    if (!rc.room(kGroupSymbols)) {
      fast = false;
      break;
    }
    ModelSet& m = models[model_set[n]];
    const int sp = sig_plane[n];
    uint8_t f = flags[n];
    const int unseen = (f & kSeen) ? 0 : 1;
    int significant = 0;
    if (sp >= 0) {
      magnitude[n] |= static_cast<uint32_t>(rc.decode(m.refine)) << p;
      low_plane[n] = plane;
      ++count;
    } else {
      const int32_t up = parent[n];
      int bucket = 0, sign_ctx = 0;
      if (up >= 0) {
        const int psp = sig_plane[up];
        bucket = psp < 0 ? 1 : 2 + std::min(psp - p, 2);
        sign_ctx = psp < 0 ? 0 : ((flags[up] & kNegative) ? 2 : 1);
      }
      significant = rc.decode(m.sig[bucket * 2 + unseen]);
      ++count;
      if (significant) {
        if (rc.decode(m.sign[sign_ctx])) f |= kNegative;
        ++count;
        sig_plane[n] = plane;
        low_plane[n] = plane;
        magnitude[n] = plane_bit;
      }
    }
    if (!kLeaves && (f & (kDescendants | kHasChildren)) == kHasChildren) {
      const int own = sp >= 0 ? 2 + std::min(sp - p - 1, 1) : significant;
      ++count;
      if (rc.decode(m.desc[own * 2 + unseen])) {
        f |= kDescendants;
        for (uint32_t c = child_begin[n]; c < child_begin[n + 1]; ++c) {
          const uint32_t child = children[c];
          reached[child >> 6] |= uint64_t{1} << (child & 63);
        }
      }
    }
    flags[n] = f | kSeen;
  }
  rc.store(dec);
  *symbols += count;
  if (fast) return true;
  // Near the end of the segment: the checked path for the rest.
  DecoderIo checked{dec};
  for (; n != end; n = next_node())
    if (!state.code_node(n, p, checked, symbols)) return false;
  return true;
}

uint32_t magnitude_of(int32_t v) {
  assert(v != INT32_MIN);
  const uint32_t m = v < 0 ? 0u - static_cast<uint32_t>(v) : static_cast<uint32_t>(v);
  return std::min<uint32_t>(m, (uint32_t{1} << (kMaxBitplane + 1)) - 1);
}

int top_bit(uint32_t x) { return x == 0 ? -1 : 31 - __builtin_clz(x); }

}  // namespace

Status validate_forest(const CoefficientForest& forest) {
  const size_t n = forest.parent.size();
  if (forest.level.size() != n || forest.context_class.size() != n)
    return invalid_argument("coefficient forest: " + std::to_string(n) + " parents but " +
                            std::to_string(forest.level.size()) + " levels and " +
                            std::to_string(forest.context_class.size()) + " context classes");
  if (n > (size_t{1} << 31) - 1) return invalid_argument("coefficient forest: too many nodes");
  for (size_t i = 0; i < n; ++i) {
    const auto where = [i] { return "coefficient forest, node " + std::to_string(i) + ": "; };
    const int level = forest.level[i];
    if (level < 1) return invalid_argument(where() + "level 0 (levels start at 1)");
    if (i > 0 && level < forest.level[i - 1])
      return invalid_argument(where() + "level " + std::to_string(level) + " after level " +
                              std::to_string(forest.level[i - 1]) + " (nodes must be sorted by level)");
    if (forest.context_class[i] >= kMaxContextClasses)
      return invalid_argument(where() + "context class " + std::to_string(forest.context_class[i]) + " >= " +
                              std::to_string(kMaxContextClasses));
    const int32_t p = forest.parent[i];
    if (p < -1 || (p >= 0 && static_cast<size_t>(p) >= i))
      return invalid_argument(where() + "parent " + std::to_string(p) + " is not -1 or an earlier node");
    if (p >= 0 && forest.level[static_cast<size_t>(p)] >= level)
      return invalid_argument(where() + "parent " + std::to_string(p) + " has level " +
                              std::to_string(forest.level[static_cast<size_t>(p)]) + ", not below " +
                              std::to_string(level));
  }
  return ok_status();
}

BitplaneStream encode_bitplanes(const CoefficientForest& forest, const std::vector<int32_t>& q) {
  assert(validate_forest(forest).ok());
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
  CoderState state(forest, index);
  size_t symbols = 0;
  for (int p = out.top_plane; p >= 0; --p) {
    for (int l = 1; l <= index.max_level; ++l) {
      EncoderIo io{magnitude, descendant_max, q, {}};
      state.code_level(p, l, io, &symbols);
      out.segments.push_back({p, l, io.enc.finish()});
    }
  }
  return out;
}

namespace {

long stream_key(const BitplaneSegmentView& s, int top_plane) {
  return static_cast<long>(top_plane - s.plane) * 256 + s.level;
}

Status validate_segments(const std::vector<BitplaneSegmentView>& segments, int top_plane, int max_forest_level) {
  long previous = -1;
  for (size_t i = 0; i < segments.size(); ++i) {
    const BitplaneSegmentView& s = segments[i];
    const std::string where = "bit-plane segment " + std::to_string(i) + " (plane " + std::to_string(s.plane) +
                              ", level " + std::to_string(s.level) + "): ";
    if (s.plane < 0 || s.plane > top_plane)
      return parse_error(where + "plane outside 0.." + std::to_string(top_plane));
    if (s.level < 1 || s.level > max_forest_level)
      return parse_error(where + "level outside 1.." + std::to_string(max_forest_level));
    if (s.data == nullptr && s.size != 0) return parse_error(where + "no data for " + std::to_string(s.size) + " bytes");
    const long key = stream_key(s, top_plane);
    if (key <= previous) return parse_error(where + "out of stream order (plane-major descending, level ascending)");
    previous = key;
  }
  return ok_status();
}

std::vector<double> reconstruct(const CoderState& state) {
  const size_t n = state.flags.size();
  double half_step[kMaxBitplane + 1];  // 2^(plane - 1): the middle of the unknown low bits
  for (int p = 0; p <= kMaxBitplane; ++p) half_step[p] = std::ldexp(1.0, p - 1);
  std::vector<double> values(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    if (state.sig_plane[i] < 0) continue;
    const double v = state.magnitude[i] + half_step[state.low_plane[i]];
    values[i] = (state.flags[i] & kNegative) ? -v : v;
  }
  return values;
}

}  // namespace

StatusOr<std::vector<double>> decode_bitplanes(const CoefficientForest& forest, int top_plane,
                                               const std::vector<BitplaneSegmentView>& segments, int max_level,
                                               BitplaneDecodeStats* stats) {
  SRCODEC_RETURN_IF_ERROR(validate_forest(forest));
  if (top_plane < -1 || top_plane > kMaxBitplane)
    return parse_error("bit planes: top plane " + std::to_string(top_plane) + " outside -1.." +
                       std::to_string(kMaxBitplane));
  if (max_level < 0) return invalid_argument("bit planes: max level " + std::to_string(max_level) + " < 0");
  const int forest_levels = forest.level.empty() ? 0 : forest.level.back();
  SRCODEC_RETURN_IF_ERROR(validate_segments(segments, top_plane, forest_levels));

  BitplaneDecodeStats local;
  BitplaneDecodeStats& st = stats ? *stats : local;
  st = BitplaneDecodeStats{};
  st.last_complete_plane = top_plane + 1;
  const ForestIndex index = build_index(forest);
  CoderState state(forest, index);
  const int levels = std::min(max_level, index.max_level);
  size_t next = 0;
  bool stopped = false;
  for (int p = top_plane; p >= 0 && !stopped; --p) {
    for (int l = 1; l <= levels && !stopped; ++l) {
      // Segments before (p, l) that were not consumed are of levels > max_level.
      const long key = stream_key({p, l, nullptr, 0}, top_plane);
      while (next < segments.size() && stream_key(segments[next], top_plane) < key) ++next;
      const bool present = next < segments.size() && segments[next].plane == p && segments[next].level == l;
      if (present) {
        ArithmeticDecoder dec(segments[next].data, segments[next].size);
        ++next;
        const bool leaves = index.child_begin[index.level_begin[l]] == index.child_begin[index.level_begin[l + 1]];
        stopped = leaves ? !decode_level<true>(state, p, l, dec, &st.symbols)
                         : !decode_level<false>(state, p, l, dec, &st.symbols);
      } else {
        stopped = true;
      }
      if (stopped) {
        st.stop_plane = p;
        st.stop_level = l;
      } else {
        ++st.segments_decoded;
      }
    }
    if (!stopped) st.last_complete_plane = p;
  }
  st.complete = !stopped;
  if (st.complete) st.last_complete_plane = 0;
  return reconstruct(state);
}

}  // namespace srcodec
