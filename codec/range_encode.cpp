// Binary range coder after G. N. N. Martin, "Range encoding: an algorithm for
// removing redundancy from a digitised message" (1979), in the byte-oriented
// form with carry propagation through a cached byte and a count of pending
// 0xFF bytes, as in LZMA's rc (I. Pavlov). Probabilities are held with 16-bit
// precision (P(0) = p / 65536) and the split is bound = (range >> 16) * p;
// range >= 2^24 keeps the split within 1/256 of the ideal.
//
// Flush: the final interval [low, low + range) has range >= 2^24. finish()
// writes the shortest prefix V (1 or 2 more bytes beyond the carried ones) such
// that EVERY continuation V, x, y, ... lies inside that interval. A decoder that
// pads with zeros therefore decodes every symbol, and even a decoder that does
// not know the padding (ok() below) sees every symbol as determined.
//
// ok(): the decoder tracks slack = the largest value the unknown bytes past the
// end could add to its code register. A 0 decision (code < bound) is
// determined only if code + slack < bound; a 1 decision (code >= bound) always
// is, since the unknown bytes only add. The same for raw bits.
#include <cassert>

#include "codec/range_coder.h"

namespace srcodec {

using range_coder_detail::kModelBits;
using range_coder_detail::kTopValue;
using range_coder_detail::update;

void ArithmeticEncoder::put_byte(uint8_t b) {
  if (!dropped_first_) {  // LZMA's leading byte: always 0, carry never reaches it
    assert(b == 0);
    dropped_first_ = true;
    return;
  }
  out_.push_back(b);
}

void ArithmeticEncoder::shift_low() {
  if (low_ < 0xFF000000u || low_ > 0xFFFFFFFFu) {
    const uint8_t carry = static_cast<uint8_t>(low_ >> 32);
    put_byte(static_cast<uint8_t>(cache_ + carry));
    for (; pending_ff_ > 0; --pending_ff_) put_byte(static_cast<uint8_t>(0xFF + carry));
    cache_ = static_cast<uint8_t>(low_ >> 24);
  } else {
    ++pending_ff_;  // top byte 0xFF: a later carry would turn it to 0x00
  }
  low_ = (low_ & 0x00FFFFFFu) << 8;
}

void ArithmeticEncoder::encode(int bit, BitModel& model) {
  const uint32_t bound = (range_ >> kModelBits) * model.p;
  if (bit == 0) {
    range_ = bound;
  } else {
    low_ += bound;
    range_ -= bound;
  }
  update(model, bit != 0);
  ++symbols_;
  while (range_ < kTopValue) {
    range_ <<= 8;
    shift_low();
  }
}

void ArithmeticEncoder::encode_raw(uint32_t value, int bits) {
  assert(bits >= 0 && bits <= 32);
  for (int i = bits - 1; i >= 0; --i) {
    range_ >>= 1;
    if ((value >> i) & 1u) low_ += range_;
    ++symbols_;
    while (range_ < kTopValue) {
      range_ <<= 8;
      shift_low();
    }
  }
}

std::vector<uint8_t> ArithmeticEncoder::finish() {
  if (symbols_ == 0) return {};
  // Shortest k such that an aligned block of 2^(32 - 8k) code values starting
  // at V fits in [low, low + range): then V's top k bytes pin every symbol.
  // k = 2 always fits because range >= 2^24 > 2 * 2^16.
  int k = 1;
  uint64_t v = 0;
  for (; k <= 4; ++k) {
    const uint64_t mask = (uint64_t{1} << (32 - 8 * k)) - 1;
    v = (low_ + mask) & ~mask;
    if (v + mask <= low_ + range_ - 1) break;
  }
  assert(k <= 2);
  low_ = v;
  for (int i = 0; i <= k; ++i) shift_low();  // k bytes of V, then flush the cache
  symbols_ = 0;
  return std::move(out_);
}

}  // namespace srcodec
