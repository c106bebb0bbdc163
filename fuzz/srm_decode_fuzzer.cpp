// libFuzzer target: the input is an .srm file handed to the public decoder
// (<srcodec/decoder.h>: decode, inspect, truncate) behind two option bytes.
//   byte 0: decode level, -1..3 (byte % 5 - 1); with bit 7 set, also
//           inspect() and truncate() to half the bytes.
//   byte 1: prefix: 0 the whole file; otherwise the first (byte & 0x7f)/127
//           of it, given as a shorter buffer (bit 7 clear) or as
//           DecodeOptions::max_bytes over the whole buffer (bit 7 set).
// An error Status is a correct answer; the sanitizers and libFuzzer's limits
// catch crashes, undefined behaviour, leaks, hangs and huge allocations.
#include <srcodec/decoder.h>

#include <cstddef>
#include <cstdint>

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

  srcodec::DecodeOptions options;
  options.level = level_byte % 5 - 1;
  options.max_vertices = kMaxVertices;
  size_t present = size;
  const unsigned fraction = prefix_byte & 0x7f;
  if (fraction != 0) {
    const uint64_t cut = static_cast<uint64_t>(size) * fraction / 127;
    if (prefix_byte & 0x80) {
      options.max_bytes = cut == 0 ? 1 : cut;  // 0 would mean "all"
    } else {
      present = static_cast<size_t>(cut);
    }
  }

  srcodec::StatusOr<srcodec::Decoded> decoded = srcodec::decode(data, present, options);
  if (decoded.ok()) {
    // Every triangle must index a decoded vertex: a bad index here is a
    // decoder bug that would crash whoever uses the mesh.
    const uint64_t n = decoded->mesh.vertex_count();
    for (uint32_t v : decoded->mesh.triangles) {
      if (v >= n) __builtin_trap();
    }
    if (decoded->bytes_used > present) __builtin_trap();
    // Crease edges name two distinct decoded vertices, the smaller first.
    for (size_t k = 0; k + 1 < decoded->crease_edges.size(); k += 2) {
      if (decoded->crease_edges[k] >= decoded->crease_edges[k + 1] || decoded->crease_edges[k + 1] >= n)
        __builtin_trap();
    }
    if (decoded->crease_edges.size() % 2 != 0) __builtin_trap();
  }
  if (level_byte & 0x80) {
    (void)srcodec::inspect(data, present);
    (void)srcodec::truncate(data, present, present / 2);
  }
  return 0;
}
