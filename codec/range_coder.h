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
//    (LZMA writes 5), see range_coder.cpp;
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

  int decode(BitModel& model);
  uint32_t decode_raw(int bits);  // 0 <= bits <= 32

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
  uint8_t next_byte();
  void normalize();

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

}  // namespace srcodec
