// The decoding half of the range coder (codec/range_coder.h); ok() and the
// slack it tracks are explained at the top of range_encode.cpp.
#include "codec/range_coder.h"

#include <cassert>

namespace srcodec {
namespace {

constexpr uint64_t kMaxSlack = 1ull << 40;  // saturation; anything >= 2^32 decides nothing

}  // namespace

ArithmeticDecoder::ArithmeticDecoder(const uint8_t* data, size_t size)
    : data_(data), size_(data == nullptr ? 0 : size) {
  for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | next_byte();
}

uint8_t ArithmeticDecoder::missing_byte() {
  slack_ = slack_ >= kMaxSlack ? kMaxSlack : (slack_ << 8) | 0xFFu;
  return 0;
}

uint32_t ArithmeticDecoder::decode_raw(int bits) {
  assert(bits >= 0 && bits <= 32);
  uint32_t value = 0;
  for (int i = 0; i < bits; ++i) {
    range_ >>= 1;
    uint32_t bit = 0;
    if (code_ >= range_) {
      code_ -= range_;
      bit = 1;
    } else if (slack_ != 0 && uint64_t{code_} + slack_ >= range_) {
      ok_ = false;
    }
    value = (value << 1) | bit;
    normalize();
  }
  return value;
}

}  // namespace srcodec
