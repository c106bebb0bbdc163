// The state both sides of the bit-plane coder keep (codec/bitplane.h): the
// forest's index, the adaptive models and what is known of every node after
// each group of symbols. The encoder (bitplane_encode.cpp) and the decoder
// (bitplane_decode.cpp) code the same groups through CoderState::code_node,
// so they stay in step by construction.
//
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
// The per-(level, class) model sets do most of the work; finer refinement
// and parent contexts gained nothing measurable, and the parent-sign context
// is kept for neighbouring detail vectors that agree in sign
// (docs/codec_design.md).
//
// Decoding checks ArithmeticDecoder::ok() after each group: a group that
// depended on bytes past the end of its segment is dropped and decoding stops
// there, so everything returned is exactly the encoder's knowledge.
//
// Raw planes (`raw_planes` > 0, .srm version 2): the segments of planes
// p < raw_planes hold raw bits instead of an arithmetic-coded stream, packed
// 8 to a byte (bit k of the segment in byte k / 8 at bit k % 8; the last byte
// padded with zeros): first the refinement bits, one per node of the level
// found significant at a plane above p, in index order (the decoder counts
// each level's significant nodes, so it knows how many), then the other
// groups' symbols in index order, one bit each (significance; sign if
// significant; D). The same symbols as a coded plane, in two passes (a
// refinement bit changes no context, so the values are the same). A cut
// segment gives the refinement bits it holds and the groups whose bits are
// all there. In the lowest planes every kind of symbol is close to even and
// the adaptive models save little (docs/codec_design.md), while
// a raw bit decodes in a fraction of a coded symbol's time.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "codec/bitplane.h"
#include "codec/range_coder.h"

namespace srcodec::bitplane_detail {

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
  // Nodes in groups of `group` consecutive ones: 3 when every run of three
  // (from node 0) is one vertex's x, y and z coefficients (one level, and
  // parents that are one earlier such run, component by component: the .srm
  // forest), else 1. The children are listed per group, in a third of the
  // memory: node n's children are the nodes in n's place of its group's
  // child groups.
  uint32_t group = 1;
  std::vector<uint32_t> child_begin;  // CSR over the groups' child groups, size groups + 1
  std::vector<uint32_t> children;     // group ids
  std::vector<uint16_t> model_set;    // per node: dense id of (level, context_class)
  size_t model_sets = 0;

  uint32_t group_of(uint32_t n) const { return group == 3 ? n / 3 : n; }
  bool has_children(uint32_t n) const {
    const uint32_t g = group_of(n);
    return child_begin[g] != child_begin[g + 1];
  }
  bool level_has_children(int level) const {
    return child_begin[group_of(level_begin[level])] != child_begin[group_of(level_begin[level + 1])];
  }
  // Sets node n's children's bits in the bitset `reached`.
  void mark_children(uint32_t n, uint64_t* reached) const {
    const uint32_t g = group_of(n), component = n - g * group;
    for (uint32_t k = child_begin[g]; k < child_begin[g + 1]; ++k) {
      const uint32_t child = children[k] * group + component;
      reached[child >> 6] |= uint64_t{1} << (child & 63);
    }
  }
};

// Derived from a valid forest; shared by encoder and decoder.
ForestIndex build_index(const CoefficientForest& f);

enum NodeFlag : uint8_t { kNegative = BitplaneValueView::kNegativeFlag, kDescendants = 2, kSeen = 4, kHasChildren = 8 };

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
  // Per level: nodes found significant so far (the refinement bits of the
  // next raw plane). Each level's entry is written by the thread decoding it.
  std::vector<uint32_t> significant_count;
  int raw_planes = 0;  // planes below this are raw (see the top)

  CoderState(const CoefficientForest& f, const ForestIndex& x, int raw = 0)
      : forest(f), index(x), models(x.model_sets), flags(f.parent.size(), 0), sig_plane(f.parent.size(), -1),
        low_plane(f.parent.size(), -1), magnitude(f.parent.size(), 0), reached((f.parent.size() + 63) / 64, 0),
        significant_count(static_cast<size_t>(x.max_level) + 2, 0), raw_planes(raw) {
    for (size_t i = 0; i < f.parent.size(); ++i) {
      if (f.parent[i] < 0) reached[i >> 6] |= uint64_t{1} << (i & 63);
      if (x.has_children(static_cast<uint32_t>(i))) flags[i] = kHasChildren;
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
      ++significant_count[forest.level[n]];
    }
    if (sp >= 0 || significant) low_plane[n] = static_cast<int8_t>(p);
    flags[n] |= kSeen;
    if (desc) {
      flags[n] |= kDescendants;
      index.mark_children(n, reached.data());
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

}  // namespace srcodec::bitplane_detail
