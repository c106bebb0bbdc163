// The decoding half of the bit-plane coder (codec/bitplane.h): the coded
// and the raw planes, sequentially or with the finest level on a second
// thread one plane behind the coarser ones.
#include <algorithm>
#include <atomic>
#include <cassert>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>

#include "codec/bitplane.h"
#include "codec/bitplane_model.h"
#include "codec/range_coder.h"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace srcodec {

using namespace bitplane_detail;

namespace {

// Bits [pos, bits) of a raw segment (see the top), read in order. Reading
// past `bits` gives 0 and leaves ok() false.
struct RawBits {
  const uint8_t* data = nullptr;
  size_t bits = 0;
  size_t pos = 0;

  int next() {
    const int bit = pos < bits ? (data[pos >> 3] >> (pos & 7)) & 1 : 0;
    ++pos;
    return bit;
  }
  bool left() const { return pos < bits; }
  bool ok() const { return pos <= bits; }
};

struct DecoderIo {
  ArithmeticDecoder& dec;

  int significance(uint32_t, int, BitModel& m) { return dec.decode(m); }
  int refine(uint32_t, int, BitModel& m) { return dec.decode(m); }
  int sign(uint32_t, BitModel& m) { return dec.decode(m); }
  int descendants(uint32_t, int, BitModel& m) { return dec.decode(m); }
  bool ok() const { return dec.ok(); }
};

// A raw plane's segment: the refinement bits, then the others (see the top).
struct RawIo {
  RawBits& refinement;
  RawBits& rest;

  int significance(uint32_t, int, BitModel&) { return rest.next(); }
  int refine(uint32_t, int, BitModel&) { return refinement.next(); }
  int sign(uint32_t, BitModel&) { return rest.next(); }
  int descendants(uint32_t, int, BitModel&) { return rest.next(); }
  bool ok() const { return refinement.ok() && rest.ok(); }
};

// What decode_level reads and writes besides the level's own node state.
// The sequential decode points everything into the CoderState; the finest
// level's thread of the pipelined decode has private copies (see
// decode_pipelined), so that no byte one thread writes is read or written by
// the other.
struct LevelContext {
  ModelSet* models;
  uint64_t* reached;            // read for the level's nodes, set for their children
  const int8_t* parent_sig;     // sig_plane of the parents
  const uint8_t* parent_flags;  // flags of the parents (only kNegative is read)
};

// The coarser thread's record of what the finest level's thread needs from
// it: nodes that became significant (sign in bit 31) and nodes whose D became
// true, in decode order. Each node appears at most once in each list.
struct EventLog {
  uint32_t* significant = nullptr;
  uint32_t* descendants = nullptr;
  size_t significant_count = 0;
  size_t descendants_count = 0;
};

// Decodes every reached node of `level` at plane p from `dec`: CoderState::
// code_node's group, written out on a register-held decoder (Cursor) while a
// whole group's bytes are there (none of its symbols can then depend on
// missing bytes), and a checked decode of the same group near the end.
// kLeaves: no node of the level has children (the finest level, most of the
// nodes), so no group has a D symbol: a shorter loop that keeps more in registers.
// `log`: where to record the level's events (nullptr: nowhere); only for
// levels with children, the only ones a finer level reads. `mark_children`:
// false when nobody reads the reached bits of the level's children (the
// level just above the pipelined decode's last one, whose thread keeps its
// own from the log); the fast path then skips them.
template <bool kLeaves>
bool decode_level(CoderState& state, const LevelContext& ctx, int p, int level, ArithmeticDecoder& dec,
                  size_t* symbols, EventLog* log, bool mark_children = true) {
  constexpr size_t kGroupSymbols = 3;
  const int32_t* const parent = state.forest.parent.data();
  const uint16_t* const model_set = state.index.model_set.data();
  ModelSet* const models = ctx.models;
  uint8_t* const flags = state.flags.data();
  int8_t* const sig_plane = state.sig_plane.data();
  const int8_t* const parent_sig = ctx.parent_sig;
  const uint8_t* const parent_flags = ctx.parent_flags;
  int8_t* const low_plane = state.low_plane.data();
  uint32_t* const magnitude = state.magnitude.data();
  uint64_t* const reached = ctx.reached;
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
  // The contexts of a node's significance and sign symbols.
  const auto parent_contexts = [&](uint32_t n, int* bucket, int* sign_ctx) {
    const int32_t up = parent[n];
    *bucket = 0;
    *sign_ctx = 0;
    if (up >= 0) {
      const int psp = parent_sig[up];
      *bucket = psp < 0 ? 1 : 2 + std::min(psp - p, 2);
      *sign_ctx = psp < 0 ? 0 : ((parent_flags[up] & kNegative) ? 2 : 1);
    }
  };
  bits = reached[w] & (~uint64_t{0} << (begin & 63));
  if (w == (end - 1) >> 6 && (end & 63) != 0) bits &= ~(~uint64_t{0} << (end & 63));
  uint32_t n = next_node();
  uint32_t newly = 0;  // nodes found significant
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
      int bucket, sign_ctx;
      parent_contexts(n, &bucket, &sign_ctx);
      significant = rc.decode(m.sig[bucket * 2 + unseen]);
      ++count;
      if (significant) {
        if (rc.decode(m.sign[sign_ctx])) f |= kNegative;
        ++count;
        ++newly;
        sig_plane[n] = plane;
        low_plane[n] = plane;
        magnitude[n] = plane_bit;
        if (!kLeaves && log != nullptr)
          log->significant[log->significant_count++] = n | (f & kNegative ? uint32_t{1} << 31 : 0);
      }
    }
    if (!kLeaves && (f & (kDescendants | kHasChildren)) == kHasChildren) {
      const int own = sp >= 0 ? 2 + std::min(sp - p - 1, 1) : significant;
      ++count;
      if (rc.decode(m.desc[own * 2 + unseen])) {
        f |= kDescendants;
        if (log != nullptr) log->descendants[log->descendants_count++] = n;
        if (mark_children) state.index.mark_children(n, reached);
      }
    }
    flags[n] = f | kSeen;
  }
  rc.store(dec);
  *symbols += count;
  state.significant_count[level] += newly;
  if (fast) return true;
  // Near the end of the segment: the checked path for the rest.
  if constexpr (kLeaves) {
    // code_node's group for a node without children, with the context's parents.
    for (; n != end; n = next_node()) {
      ModelSet& m = models[model_set[n]];
      const int sp = sig_plane[n];
      const uint8_t f = flags[n];
      int refine = 0, significant = 0, negative = 0;
      if (sp >= 0) {
        refine = dec.decode(m.refine);
      } else {
        int bucket, sign_ctx;
        parent_contexts(n, &bucket, &sign_ctx);
        significant = dec.decode(m.sig[bucket * 2 + ((f & kSeen) ? 0 : 1)]);
        if (significant) negative = dec.decode(m.sign[sign_ctx]);
      }
      if (!dec.ok()) return false;
      *symbols += 1 + static_cast<size_t>(significant);
      if (sp >= 0) {
        magnitude[n] |= static_cast<uint32_t>(refine) << p;
      } else if (significant) {
        sig_plane[n] = plane;
        magnitude[n] = plane_bit;
        ++state.significant_count[level];
      }
      if (sp >= 0 || significant) low_plane[n] = plane;
      flags[n] = static_cast<uint8_t>(f | kSeen | (negative ? kNegative : 0));
    }
  } else {
    // Only the coarser levels get here, which always use the CoderState's own
    // arrays: code_node reads and writes those.
    assert(ctx.models == state.models.data() && ctx.reached == state.reached.data());
    DecoderIo checked{dec};
    for (; n != end; n = next_node()) {
      const int8_t sp_before = sig_plane[n];
      const uint8_t f_before = flags[n];
      if (!state.code_node(n, p, checked, symbols)) return false;
      if (log != nullptr) {
        if (sp_before < 0 && sig_plane[n] >= 0)
          log->significant[log->significant_count++] = n | (flags[n] & kNegative ? uint32_t{1} << 31 : 0);
        if (!(f_before & kDescendants) && (flags[n] & kDescendants)) log->descendants[log->descendants_count++] = n;
      }
    }
  }
  return true;
}

// Bit i set when node 64 w + i is in [begin, end) and significant
// (sig_plane >= 0). Reads only the level's own sig_plane bytes, so that the
// pipelined decode's threads never read what the other writes.
uint64_t significant_mask(const int8_t* sig_plane, uint32_t w, uint32_t begin, uint32_t end) {
  const uint32_t first = w << 6;
  if (first >= begin && end - first >= 64) {
#if defined(__SSE2__)
    uint64_t insignificant = 0;  // the sign bits of the 64 bytes
    for (int k = 0; k < 4; ++k) {
      const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(sig_plane + first + 16 * k));
      insignificant |= uint64_t{static_cast<uint32_t>(_mm_movemask_epi8(v))} << (16 * k);
    }
    return ~insignificant;
#endif
  }
  uint64_t mask = 0;
  for (uint32_t n = std::max(first, begin); n < std::min(first + 64, end); ++n)
    mask |= uint64_t{sig_plane[n] >= 0 ? 1u : 0u} << (n - first);
  return mask;
}

// A raw plane's segment of a level without children (the finest level, most
// of the nodes), in its two passes over the reached nodes: the refinement
// bits of the nodes already significant, then significance and sign of the
// others. Each pass visits only its own nodes (masks from sig_plane, 64
// nodes at a time) and decodes without a branch on the bits, so nothing is
// mispredicted per node. `refinement_complete`: the segment holds all the
// refinement bits (else only those are used).
bool decode_leaves_raw(CoderState& state, const LevelContext& ctx, int p, int level, RawBits& refinement,
                       RawBits& rest, bool refinement_complete, size_t* symbols) {
  uint8_t* const flags = state.flags.data();
  int8_t* const sig_plane = state.sig_plane.data();
  int8_t* const low_plane = state.low_plane.data();
  uint32_t* const magnitude = state.magnitude.data();
  const uint64_t* const reached = ctx.reached;
  const int8_t plane = static_cast<int8_t>(p);
  const uint32_t begin = state.index.level_begin[level], end = state.index.level_begin[level + 1];
  if (begin >= end) return true;
  const uint32_t first_word = begin >> 6, last_word = (end - 1) >> 6;

  // Pass 1: the refinement bits, as far as they go.
  size_t count = 0;
  for (uint32_t w = first_word; w <= last_word && refinement.left(); ++w) {
    uint64_t bits = reached[w] & significant_mask(sig_plane, w, begin, end);
    while (bits != 0 && refinement.left()) {
      const uint32_t n = (w << 6) | static_cast<uint32_t>(__builtin_ctzll(bits));
      bits &= bits - 1;
      magnitude[n] |= static_cast<uint32_t>(refinement.next()) << p;
      low_plane[n] = plane;
      ++count;
    }
  }
  *symbols += count;
  if (!refinement_complete) return false;

  // Pass 2: significance and sign of the reached nodes not yet significant:
  // two bits read at once, the second used (and consumed) only after a 1.
  const uint8_t* const data = rest.data;
  size_t pos = rest.pos;
  // While pos + 9 <= bits (pos < fast_end), the bytes at pos / 8 and pos / 8 + 1 are there.
  const size_t fast_end = rest.bits >= 9 ? rest.bits - 8 : 0;
  uint32_t newly = 0;
  count = 0;
  for (uint32_t w = first_word; w <= last_word; ++w) {
    uint64_t bits = reached[w] & ~significant_mask(sig_plane, w, begin, end);
    if (w == first_word) bits &= ~uint64_t{0} << (begin & 63);
    if (w == last_word && (end & 63) != 0) bits &= ~(~uint64_t{0} << (end & 63));
    while (bits != 0) {
      const uint32_t n = (w << 6) | static_cast<uint32_t>(__builtin_ctzll(bits));
      uint32_t significant, negative;
      if (pos < fast_end) {
        const uint32_t window = (uint32_t{data[pos >> 3]} | (uint32_t{data[(pos >> 3) + 1]} << 8)) >> (pos & 7);
        significant = window & 1u;
        negative = (window >> 1) & significant;
        pos += 1 + significant;
      } else {
        // Near the end: a group whose bits are not all there ends decoding.
        rest.pos = pos;
        significant = static_cast<uint32_t>(rest.next());
        negative = significant ? static_cast<uint32_t>(rest.next()) : 0u;
        if (!rest.ok()) {
          *symbols += count;
          state.significant_count[level] += newly;
          return false;
        }
        pos = rest.pos;
      }
      bits &= bits - 1;
      // Insignificant nodes have sig_plane and low_plane -1 and magnitude 0.
      const int8_t now = static_cast<int8_t>(static_cast<int>(significant) * (p + 1) - 1);
      sig_plane[n] = now;
      low_plane[n] = now;
      magnitude[n] = significant << p;
      flags[n] = static_cast<uint8_t>(flags[n] | kSeen | (negative ? kNegative : 0));
      newly += significant;
      count += 1 + significant;
    }
  }
  rest.pos = pos;
  *symbols += count;
  state.significant_count[level] += newly;
  return true;
}

// A raw plane's segment of a level with children (a coarser level: the
// CoderState's own context), group by group with code_node. When a group's
// bits are not all there, decoding stops, and the refinement bits of that
// node and the later ones are still used.
bool decode_raw_level(CoderState& state, const LevelContext& ctx, int p, int level, RawBits& refinement,
                      RawBits& rest, bool refinement_complete, size_t* symbols, EventLog* log) {
  assert(ctx.models == state.models.data() && ctx.reached == state.reached.data());
  (void)ctx;
  uint32_t stopped = 0;
  bool complete = refinement_complete;
  if (complete) {
    RawIo io{refinement, rest};
    complete = state.for_reached(level, [&](uint32_t n) {
      const int8_t sp_before = state.sig_plane[n];
      const uint8_t f_before = state.flags[n];
      const size_t refinement_before = refinement.pos, rest_before = rest.pos;
      if (!state.code_node(n, p, io, symbols)) {
        refinement.pos = refinement_before;
        rest.pos = rest_before;
        stopped = n;
        return false;
      }
      if (log != nullptr) {
        if (sp_before < 0 && state.sig_plane[n] >= 0)
          log->significant[log->significant_count++] = n | (state.flags[n] & kNegative ? uint32_t{1} << 31 : 0);
        if (!(f_before & kDescendants) && (state.flags[n] & kDescendants))
          log->descendants[log->descendants_count++] = n;
      }
      return true;
    });
    if (complete) return true;
  }
  state.for_reached(level, [&](uint32_t n) {
    if (n >= stopped && state.sig_plane[n] >= 0 && refinement.left()) {
      state.magnitude[n] |= static_cast<uint32_t>(refinement.next()) << p;
      state.low_plane[n] = static_cast<int8_t>(p);
      ++*symbols;
    }
    return true;
  });
  return false;
}

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

LevelContext own_context(CoderState& state) {
  return {state.models.data(), state.reached.data(), state.sig_plane.data(), state.flags.data()};
}

// Decodes (p, l) from `segment` with the context `ctx`; false when the
// segment ended before the level did.
bool decode_segment(CoderState& state, const LevelContext& ctx, const BitplaneSegmentView& segment, int p, int l,
                    size_t* symbols, EventLog* log, bool mark_children = true) {
  const bool leaves = !state.index.level_has_children(l);
  if (p >= state.raw_planes) {
    ArithmeticDecoder dec(segment.data, segment.size);
    return leaves ? decode_level<true>(state, ctx, p, l, dec, symbols, nullptr)
                  : decode_level<false>(state, ctx, p, l, dec, symbols, log, mark_children);
  }
  // A raw plane: the refinement bits (one per node of the level already
  // significant), then the rest.
  const size_t refinement_bits = state.significant_count[static_cast<size_t>(l)];
  const size_t present = segment.size > SIZE_MAX / 8 ? SIZE_MAX : 8 * segment.size;  // bits
  RawBits refinement{segment.data, std::min(refinement_bits, present), 0};
  RawBits rest{segment.data, present, std::min(refinement_bits, present)};
  const bool complete = present >= refinement_bits;
  return leaves ? decode_leaves_raw(state, ctx, p, l, refinement, rest, complete, symbols)
                : decode_raw_level(state, ctx, p, l, refinement, rest, complete, symbols, log);
}

// Per (plane, level), the index of its segment in `segments`, or -1. The
// segments are in strictly increasing stream order (validate_segments), so
// this finds what the sequential scan of the list finds.
std::vector<int> segment_table(const std::vector<BitplaneSegmentView>& segments, int top_plane, int levels) {
  std::vector<int> table(static_cast<size_t>(top_plane + 1) * static_cast<size_t>(levels), -1);
  for (size_t i = 0; i < segments.size(); ++i)
    if (segments[i].level <= levels)
      table[static_cast<size_t>(top_plane - segments[i].plane) * levels + (segments[i].level - 1)] =
          static_cast<int>(i);
  return table;
}

void decode_sequential(CoderState& state, int top_plane, const std::vector<BitplaneSegmentView>& segments,
                       int levels, BitplaneDecodeStats& st) {
  const std::vector<int> table = segment_table(segments, top_plane, levels);
  const LevelContext ctx = own_context(state);
  bool stopped = false;
  for (int p = top_plane; p >= 0 && !stopped; --p) {
    for (int l = 1; l <= levels && !stopped; ++l) {
      const int k = table[static_cast<size_t>(top_plane - p) * levels + (l - 1)];
      // A missing segment ends decoding as a short one does.
      stopped = k < 0 || !decode_segment(state, ctx, segments[k], p, l, &st.symbols, nullptr);
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
}

// The pipelined decode: this thread decodes levels 1 .. L-1 plane by plane
// (the coarser thread), a second thread decodes level L (the forest's last,
// so its nodes have no children and nothing coarser reads their state) one
// plane behind. Level L at plane p reads only
//  - its own nodes' state and models (only the second thread writes them:
//    it gets its own copy of the models, the CoderState's arrays are written
//    per node, so the threads write different bytes);
//  - the parents' significance plane and sign as of plane p, and which of
//    its nodes are reached as of plane p: the coarser thread may already be
//    changing those at plane p - 1, so it logs its events (EventLog) and
//    publishes per plane how far the log goes; the second thread replays
//    them into private copies before decoding the plane.
// Outcomes equal the sequential decode's, stats included, except when level
// L stops at plane p (a short or missing segment) after the coarser thread
// has already decoded part of plane p - 1, which the sequential decode would
// never have touched: returns false then (only corrupt input: in a cut file
// the short segment is the last one), and the caller decodes again sequentially.
bool decode_pipelined(CoderState& state, int top_plane, const std::vector<BitplaneSegmentView>& segments, int levels,
                      BitplaneDecodeStats& st, const CoarseLevelsDone& coarse_done) {
  const ForestIndex& index = state.index;
  const int L = levels;
  const uint32_t coarse_nodes = index.level_begin[L];
  const std::vector<int> table = segment_table(segments, top_plane, levels);
  // Everything the second thread uses is allocated here, so that it cannot fail.
  std::unique_ptr<uint32_t[]> significant(new uint32_t[coarse_nodes + 1]);
  std::unique_ptr<uint32_t[]> descendants(new uint32_t[coarse_nodes + 1]);
  EventLog log{significant.get(), descendants.get(), 0, 0};
  std::vector<size_t> significant_end(static_cast<size_t>(top_plane + 1)), descendants_end(significant_end.size());
  std::vector<ModelSet> fine_models(state.models.size());
  std::vector<uint64_t> fine_reached = state.reached;  // the roots; D events add the rest
  std::vector<int8_t> fine_parent_sig(coarse_nodes, -1);
  std::vector<uint8_t> fine_parent_flags(coarse_nodes, 0);
  const LevelContext fine_ctx{fine_models.data(), fine_reached.data(), fine_parent_sig.data(),
                              fine_parent_flags.data()};

  std::mutex mutex;
  std::condition_variable published;
  int done_plane = top_plane + 1;  // the coarser thread finished planes >= done_plane
  bool coarse_finished = false;    // ... and will finish no more
  std::atomic<int> fine_stop{-1};  // plane where level L stopped, -1: not (yet)
  size_t fine_symbols = 0, fine_segments = 0;

  const auto fine = [&] {
    size_t sig_read = 0, desc_read = 0;
    for (int p = top_plane; p >= 0; --p) {
      size_t sig_end, desc_end;
      {
        std::unique_lock<std::mutex> lock(mutex);
        published.wait(lock, [&] { return done_plane <= p || coarse_finished; });
        if (done_plane > p) return;  // the coarser levels stopped in plane p
        sig_end = significant_end[static_cast<size_t>(top_plane - p)];
        desc_end = descendants_end[static_cast<size_t>(top_plane - p)];
      }
      for (; sig_read < sig_end; ++sig_read) {
        const uint32_t e = significant[sig_read], u = e & ~(uint32_t{1} << 31);
        fine_parent_sig[u] = static_cast<int8_t>(p);
        fine_parent_flags[u] = (e >> 31) ? kNegative : 0;
      }
      for (; desc_read < desc_end; ++desc_read) {
        const uint32_t u = descendants[desc_read];
        index.mark_children(u, fine_reached.data());
      }
      const int k = table[static_cast<size_t>(top_plane - p) * levels + (L - 1)];
      if (k < 0) {
        fine_stop.store(p, std::memory_order_release);
        return;
      }
      if (!decode_segment(state, fine_ctx, segments[k], p, L, &fine_symbols, nullptr)) {
        fine_stop.store(p, std::memory_order_release);
        return;
      }
      ++fine_segments;
    }
  };
  std::thread fine_thread;
  try {
    fine_thread = std::thread(fine);
  } catch (const std::system_error&) {
    return false;  // no thread: nothing decoded yet, the sequential decode does it all
  }
  // Ends and joins the second thread however this function is left.
  const auto finish = [&] {
    {
      std::lock_guard<std::mutex> lock(mutex);
      coarse_finished = true;
      published.notify_one();
    }
    if (fine_thread.joinable()) fine_thread.join();
  };
  struct Finisher {
    const decltype(finish)& f;
    ~Finisher() { f(); }
  } finisher{finish};

  // The coarser levels. Stops also when level L has stopped above the plane
  // (whatever the sequential decode would not have decoded stays untouched).
  const LevelContext ctx = own_context(state);
  int lowest_entered = top_plane + 1;  // lowest plane where a coarser segment was decoded
  int coarse_stop_plane = -1, coarse_stop_level = -1;
  size_t coarse_symbols = 0, coarse_segments = 0;
  for (int p = top_plane; p >= 0 && coarse_stop_plane < 0; --p) {
    if (fine_stop.load(std::memory_order_acquire) > p) break;
    for (int l = 1; l < L; ++l) {
      const int k = table[static_cast<size_t>(top_plane - p) * levels + (l - 1)];
      if (k >= 0) lowest_entered = p;
      // Level L - 1's children are all of level L, whose reached bits only
      // the second thread's own copy holds.
      if (k < 0 || !decode_segment(state, ctx, segments[k], p, l, &coarse_symbols, &log, l != L - 1)) {
        coarse_stop_plane = p;
        coarse_stop_level = l;
        break;
      }
      ++coarse_segments;
    }
    if (coarse_stop_plane >= 0) break;
    std::lock_guard<std::mutex> lock(mutex);
    significant_end[static_cast<size_t>(top_plane - p)] = log.significant_count;
    descendants_end[static_cast<size_t>(top_plane - p)] = log.descendants_count;
    done_plane = p;
    published.notify_one();
  }
  // The coarser levels are final (the finest level's thread writes only its
  // own nodes' state): the caller may work on them meanwhile.
  if (coarse_done)
    coarse_done(BitplaneValueView(state.magnitude.data(), state.low_plane.data(), state.flags.data(), coarse_nodes));
  finish();

  const int fine_stop_plane = fine_stop.load(std::memory_order_acquire);
  if (fine_stop_plane >= 0 && lowest_entered < fine_stop_plane) return false;
  st.symbols = coarse_symbols + fine_symbols;
  st.segments_decoded = coarse_segments + fine_segments;
  // The first stop in stream order: level L at plane p comes before every
  // coarser level at plane p - 1 and after the coarser ones at plane p (which
  // it waits for, so it cannot stop where they did).
  if (fine_stop_plane >= 0) {
    st.stop_plane = fine_stop_plane;
    st.stop_level = L;
  } else if (coarse_stop_plane >= 0) {
    st.stop_plane = coarse_stop_plane;
    st.stop_level = coarse_stop_level;
  }
  st.complete = st.stop_plane < 0;
  st.last_complete_plane = st.complete ? 0 : st.stop_plane + 1;
  st.coarse_done_final = static_cast<bool>(coarse_done);
  return true;
}

// Below this many nodes in the finest level, a thread costs more than it saves.
constexpr uint32_t kPipelineMinNodes = 1 << 14;

// The decoder's result, taken from its state.
BitplaneValues values_of(CoderState& state) {
  return BitplaneValues(std::move(state.magnitude), std::move(state.low_plane), std::move(state.flags));
}

}  // namespace

std::vector<double> BitplaneValues::values() const {
  const BitplaneValueView all = view();
  std::vector<double> out(size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = all.value(i);
  return out;
}

StatusOr<std::vector<double>> decode_bitplanes(const CoefficientForest& forest, int top_plane,
                                               const std::vector<BitplaneSegmentView>& segments, int max_level,
                                               BitplaneDecodeStats* stats, BitplaneThreads threads, int raw_planes) {
  StatusOr<BitplaneValues> decoded =
      decode_bitplane_values(forest, top_plane, segments, max_level, stats, threads, raw_planes);
  if (!decoded.ok()) return decoded.status();
  return decoded->values();
}

StatusOr<BitplaneValues> decode_bitplane_values(const CoefficientForest& forest, int top_plane,
                                                const std::vector<BitplaneSegmentView>& segments, int max_level,
                                                BitplaneDecodeStats* stats, BitplaneThreads threads, int raw_planes,
                                                const CoarseLevelsDone& coarse_done) {
  SRCODEC_RETURN_IF_ERROR(validate_forest(forest));
  if (raw_planes < 0 || raw_planes > kMaxBitplane + 1)
    return parse_error("bit planes: " + std::to_string(raw_planes) + " raw planes, outside 0.." +
                       std::to_string(kMaxBitplane + 1));
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
  const int levels = std::min(max_level, index.max_level);
  // The pipeline needs a last level (no children) below at least one coarser one.
  const bool can_pipeline = threads != BitplaneThreads::kSequential && top_plane >= 0 && levels >= 2 &&
                            levels == index.max_level;
  // (On one core the second thread would only add its event replay.)
  static const bool several_cores = std::thread::hardware_concurrency() > 1;
  const bool big = index.level_begin[levels + 1] - index.level_begin[levels] >= kPipelineMinNodes;
  if (can_pipeline && (threads == BitplaneThreads::kPipelined || (several_cores && big))) {
    CoderState state(forest, index, raw_planes);
    if (decode_pipelined(state, top_plane, segments, levels, st, coarse_done)) return values_of(state);
    st = BitplaneDecodeStats{};
    st.last_complete_plane = top_plane + 1;
  }
  CoderState state(forest, index, raw_planes);
  decode_sequential(state, top_plane, segments, levels, st);
  return values_of(state);
}

}  // namespace srcodec