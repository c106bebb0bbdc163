// Adaptive binary arithmetic coder: a 32-bit range coder with byte-wise carry
// propagation (the "cache + pending 0xFF" scheme of LZMA's rc), 16-bit
// probabilities and a shift-based probability update whose rate starts fast
// and settles (state counter per model, see BitModel).
//
// Probabilities are kept with 16-bit precision (more than the 12 bits of
// LZMA) so that slow adaptation can still represent p near 0 or 1.
//
// Differences from LZMA's coder, for short per-segment streams:
//  - the always-zero first byte of LZMA's stream is not written;
//  - finish() writes only the 1 or 2 bytes that pin the final interval
//    (LZMA writes 5), see range_encode.cpp;
//  - the decoder knows which symbols were fully determined by real bytes
//    (ok()), so any prefix of a stream decodes safely.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace srcodec {

// Adaptive estimate of P(bit == 0) in units of 1/65536. The adaptation shift
// grows with the number of symbols seen (1, 2, 2, 3, ... up to kMaxShift), so
// a fresh model learns quickly and a busy one estimates precisely.
struct BitModel {
  uint16_t p = 32768;  // probability of 0, always in [1, 65535]
  uint8_t seen = 0;    // symbols coded with this model, saturating
};

namespace range_coder_detail {

constexpr uint32_t kTopValue = 1u << 24;  // normalize when range drops below
constexpr int kModelBits = 16;
constexpr uint32_t kModelOne = 1u << kModelBits;
constexpr int kMaxShift = 7;  // slowest adaptation: rate 1/128 (faster floors cost bytes: docs/codec_design.md)

// Adaptation shift after `seen` symbols: about log2(seen + 2), i.e. a rate
// near 1/(seen + 2) (a running mean) until it reaches 2^-kMaxShift.
constexpr int shift_for(int seen) {
  int s = 1;
  while (s < kMaxShift && (1 << s) + (1 << (s - 1)) <= seen + 2) ++s;
  return s;
}
// Models stop counting once the rate is final.
constexpr int kSeenLimit = [] {
  int n = 0;
  while (shift_for(n) < kMaxShift) ++n;
  return n;
}();
static_assert(kSeenLimit < 255, "seen counter must fit in uint8_t");

// shift_for(seen) for every value `seen` takes, looked up rather than looped.
struct ShiftTable {
  uint8_t shift[kSeenLimit + 1];
};
constexpr ShiftTable kShiftTable = [] {
  ShiftTable t{};
  for (int i = 0; i <= kSeenLimit; ++i) t.shift[i] = static_cast<uint8_t>(shift_for(i));
  return t;
}();

// `bit` is 0 or 1. Written with a mask rather than `?:`, which compilers may
// turn into a branch on the bit (see ArithmeticDecoder::Cursor::decode).
inline void update(BitModel& m, int bit) {
  const int s = kShiftTable.shift[m.seen];
  const uint32_t p = m.p;
  const uint32_t one = 0u - static_cast<uint32_t>(bit);  // all ones when the bit is 1
  m.p = static_cast<uint16_t>(p + (((kModelOne - p) >> s) & ~one) - ((p >> s) & one));
  m.seen = static_cast<uint8_t>(m.seen + (m.seen < kSeenLimit ? 1 : 0));
}

}  // namespace range_coder_detail

class ArithmeticEncoder {
 public:
  // Codes `bit` (0 or 1; any non-zero value counts as 1) and adapts `model`.
  void encode(int bit, BitModel& model);
  // Codes the low `bits` bits of `value` (MSB first) with probability 1/2 each.
  // 0 <= bits <= 32.
  void encode_raw(uint32_t value, int bits);
  // Flushes and returns the stream; the encoder is spent afterwards.
  // Empty if nothing was encoded. Otherwise every symbol decodes from the
  // returned bytes with ArithmeticDecoder::ok() staying true.
  std::vector<uint8_t> finish();
  // True while no symbol has been encoded.
  bool empty() const { return symbols_ == 0; }

 private:
  void shift_low();
  void put_byte(uint8_t b);

  uint64_t low_ = 0;            // 32 bits of interval base + 1 carry bit
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;           // last byte not yet written (carry may reach it)
  uint64_t pending_ff_ = 0;     // 0xFF bytes after cache_, waiting for carry
  bool dropped_first_ = false;  // the very first cache byte is always 0: not written
  uint64_t symbols_ = 0;
  std::vector<uint8_t> out_;
};

// Decodes a stream written by ArithmeticEncoder. Safe on any bytes: reads
// only inside [data, data + size) and returns zeros past the end.
class ArithmeticDecoder {
 public:
  ArithmeticDecoder(const uint8_t* data, size_t size);  // size may be 0

  inline int decode(BitModel& model);
  uint32_t decode_raw(int bits);  // 0 <= bits <= 32

  // A modeled symbol reads at most this many bytes (range >= 2^24 before it,
  // >= 2^8 after the split, since 1 <= p <= 65535).
  static constexpr size_t kMaxBytesPerSymbol = 2;
  // The decoder's state copied into a value that a hot loop keeps in
  // registers (the decoder's own members would be reloaded after every store
  // through a byte pointer). While room() allows, its decode() gives the same
  // symbol and state as the decoder's, without the checks for missing bytes
  // (none can be read, so ok() cannot change). The decoder itself must not be
  // used until store() has written the state back.
  class Cursor {
   public:
    explicit Cursor(const ArithmeticDecoder& d)
        : range_(d.range_), code_(d.code_), next_(d.data_ + d.pos_), last_(d.data_ + d.size_), base_(d.data_) {}
    // True when `symbols` more symbols can be decoded here.
    bool room(size_t symbols) const {
      return static_cast<size_t>(last_ - next_) >= symbols * kMaxBytesPerSymbol;
    }
    void store(ArithmeticDecoder& d) const {
      d.range_ = range_;
      d.code_ = code_;
      d.pos_ = static_cast<size_t>(next_ - base_);
    }
    int decode(BitModel& model) {
      // Without branches on the bit (masks, not `?:`, which GCC compiled to a
      // branch): the bits of the data are not predictable (refinement bits
      // are about even), and a mispredicted branch costs more than the
      // arithmetic of both sides.
      const uint32_t bound = (range_ >> range_coder_detail::kModelBits) * model.p;
      const uint32_t bit = code_ >= bound ? 1u : 0u;
      const uint32_t one = 0u - bit;  // all ones when the bit is 1
      code_ -= bound & one;
      range_ = ((range_ - bound) & one) | (bound & ~one);
      range_coder_detail::update(model, static_cast<int>(bit));
      // Normalize without branches: range >= 2^8 here, so 0, 1 or 2 bytes
      // (whole bytes of leading zeros beyond the top 8 bits) come in; room()
      // vouched for the 2 bytes read.
      const int bytes = __builtin_clz(range_) >> 3;
      const uint32_t two = (uint32_t{next_[0]} << 8) | next_[1];
      code_ = (code_ << (8 * bytes)) | (two >> (16 - 8 * bytes));
      range_ <<= 8 * bytes;
      next_ += bytes;
      return static_cast<int>(bit);
    }

   private:
    uint32_t range_, code_;
    const uint8_t* next_;
    const uint8_t* last_;
    const uint8_t* base_;
  };

  // True while every symbol decoded so far was determined by real bytes: the
  // same symbol would come out whatever bytes followed the end of the data.
  // Once a symbol depended on the missing bytes, ok() stays false.
  // GUARANTEE: if `data` is a prefix of an encoder's output, every symbol
  // decoded while ok() is still true afterwards equals the encoder's symbol;
  // on the complete output ok() stays true for all encoded symbols.
  bool ok() const { return ok_; }
  // Bytes taken from the real data so far (at most size).
  size_t bytes_consumed() const { return pos_; }

 private:
  uint8_t next_byte() {
    if (pos_ < size_) return data_[pos_++];  // slack_ is 0: real bytes come before any missing one
    return missing_byte();
  }
  uint8_t missing_byte();
  void normalize() {
    while (range_ < range_coder_detail::kTopValue) {
      range_ <<= 8;
      code_ = (code_ << 8) | next_byte();
    }
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t code_ = 0;
  // The true code (with the real continuation of the data) lies in
  // [code_, code_ + slack_]; slack_ grows by one byte per missing byte read.
  uint64_t slack_ = 0;
  bool ok_ = true;
};

inline int ArithmeticDecoder::decode(BitModel& model) {
  const uint32_t bound = (range_ >> range_coder_detail::kModelBits) * model.p;
  int bit;
  if (code_ < bound) {
    if (slack_ != 0 && uint64_t{code_} + slack_ >= bound) ok_ = false;
    range_ = bound;
    bit = 0;
  } else {
    code_ -= bound;
    range_ -= bound;
    bit = 1;
  }
  range_coder_detail::update(model, bit);
  normalize();
  return bit;
}

}  // namespace srcodec
