// libFuzzer target: the input is an .srm file read the way `srcodec decode`
// reads one (parse_srm, then decode_srm), behind two option bytes.
//   byte 0: decode level, -1..3 (byte % 5 - 1); with bit 7 set, parse_srm
//           also loads only the chunks that level needs (SrmReadOptions.max_level).
//   byte 1: prefix: 0 the whole file; otherwise the first (byte & 0x7f)/127
//           of it, given as a shorter buffer (bit 7 clear) or as
//           SrmReadOptions.max_bytes over the whole buffer (bit 7 set).
// A parse or decode error is a correct answer; the sanitizers and libFuzzer's
// limits catch crashes, undefined behaviour, leaks, hangs and huge allocations.
#include <cstddef>
#include <cstdint>

#include "codec/srm_codec.h"
#include "format/srm/srm_file.h"

namespace {

// Small enough that a tiny file describing a huge uniform mesh is refused
// instead of exhausting the fuzzer's memory (about 500 bytes a vertex).
constexpr uint64_t kMaxVertices = 100000;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  const uint8_t level_byte = data[0];
  const uint8_t prefix_byte = data[1];
  data += 2;
  size -= 2;

  const int level = level_byte % 5 - 1;
  srcodec::SrmReadOptions read;
  if (level_byte & 0x80) read.max_level = level;

  size_t present = size;
  const unsigned fraction = prefix_byte & 0x7f;
  if (fraction != 0) {
    const uint64_t cut = static_cast<uint64_t>(size) * fraction / 127;
    if (prefix_byte & 0x80) {
      read.max_bytes = cut == 0 ? 1 : cut;  // 0 would mean "all"
    } else {
      present = static_cast<size_t>(cut);
    }
  }

  srcodec::StatusOr<srcodec::SrmFile> file = srcodec::parse_srm(data, present, read);
  if (!file.ok()) return 0;

  srcodec::SrmDecodeOptions options;
  options.level = level;
  options.max_vertices = kMaxVertices;
  srcodec::StatusOr<srcodec::DecodedSrm> decoded = srcodec::decode_srm(file.value(), options);
  if (decoded.ok()) {
    // Every triangle must index a decoded vertex: a bad index here is a
    // decoder bug that would crash whoever uses the mesh.
    const auto n = static_cast<int64_t>(decoded->mesh.positions.size());
    for (const auto& t : decoded->mesh.triangles) {
      for (int k = 0; k < 3; ++k) {
        if (t[k] < 0 || t[k] >= n) __builtin_trap();
      }
    }
  }
  return 0;
}
