// Little-endian byte writing and bounds-checked reading for the .srm file.
// The reader never reads outside its buffer: every read reports failure
// instead, and the caller turns that into a Status naming the field and the
// byte offset (format/srm/README.md).
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "format/status.h"

namespace srcodec {

class ByteWriter {
 public:
  void u8(uint8_t v) { bytes_.push_back(v); }
  void u16(uint16_t v) { put_le(v, 2); }
  void u32(uint32_t v) { put_le(v, 4); }
  void f32(float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    u32(bits);
  }
  void f64(double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, 8);
    put_le(bits, 8);
  }
  // LEB128: 7 bits a byte, low first.
  void varint(uint64_t v) {
    while (v >= 0x80) {
      bytes_.push_back(static_cast<uint8_t>(v | 0x80));
      v >>= 7;
    }
    bytes_.push_back(static_cast<uint8_t>(v));
  }
  void bytes(const std::vector<uint8_t>& b) { bytes_.insert(bytes_.end(), b.begin(), b.end()); }
  std::vector<uint8_t>& data() { return bytes_; }
  size_t size() const { return bytes_.size(); }

 private:
  void put_le(uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
  }
  std::vector<uint8_t> bytes_;
};

class ByteReader {
 public:
  // `base_offset`: where data[0] sits in the file, for error messages.
  ByteReader(const uint8_t* data, size_t size, size_t base_offset = 0)
      : data_(data), size_(size), base_(base_offset) {}

  bool u8(uint8_t& v) { return get_le(v, 1); }
  bool u16(uint16_t& v) { return get_le(v, 2); }
  bool u32(uint32_t& v) { return get_le(v, 4); }
  bool f32(float& v) {
    uint32_t bits;
    if (!u32(bits)) return false;
    std::memcpy(&v, &bits, 4);
    return true;
  }
  bool f64(double& v) {
    uint64_t bits;
    if (!get_le(bits, 8)) return false;
    std::memcpy(&v, &bits, 8);
    return true;
  }
  bool varint(uint64_t& v) {
    v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      uint8_t b;
      if (!u8(b)) return false;
      v |= static_cast<uint64_t>(b & 0x7f) << shift;
      if (!(b & 0x80)) return true;
    }
    return false;  // more than 10 bytes: not a varint we wrote
  }
  size_t position() const { return pos_; }         // within this buffer
  size_t file_offset() const { return base_ + pos_; }
  size_t remaining() const { return size_ - pos_; }

  // "<what> at byte <offset>: <problem>"
  Status error(const std::string& what, const std::string& problem) const {
    return parse_error(what + " at byte " + std::to_string(file_offset()) + ": " + problem);
  }

 private:
  template <typename T>
  bool get_le(T& v, int n) {
    if (size_ - pos_ < static_cast<size_t>(n)) return false;
    uint64_t x = 0;
    for (int i = 0; i < n; ++i) x |= static_cast<uint64_t>(data_[pos_ + i]) << (8 * i);
    pos_ += n;
    v = static_cast<T>(x);
    return true;
  }
  const uint8_t* data_;
  size_t size_;
  size_t base_;
  size_t pos_ = 0;
};

}  // namespace srcodec
