// The .srm container, version 1 (byte layout: format/README.md): a header
// with counts, bounding box, quantization and the table of every chunk's
// length and checksum, then the base mesh chunk, one refinement-flag chunk per
// level, and the coefficient segments in embedded order (bit-plane major,
// level minor). Any prefix that holds the whole header parses: chunks past the
// cut are missing or partial, and the decoder makes the best mesh of them.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

#include "format/status.h"

namespace srcodec {

inline constexpr uint8_t kSrmVersion = 1;
inline constexpr int kSrmMaxLevels = 12;
inline constexpr int kSrmMaxPlane = 30;
inline constexpr int kSrmComponents = 3;

struct SrmChunkEntry {
  uint64_t length = 0;
  uint32_t crc = 0;  // CRC-32 for base and flags; only the low 16 bits are stored for segments
};

struct SrmHeader {
  uint64_t input_vertices = 0;   // of the original mesh: the bpv denominator
  uint64_t input_triangles = 0;
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero(), bbox_max = Eigen::Vector3d::Zero();  // original mesh
  int levels = 0;                // finest level L, 0..kSrmMaxLevels
  int base_bits = 12;            // base position grid: bits per coordinate
  double grid_step = 1.0;        // grid spacing; origin bbox_min
  uint64_t base_vertices = 0, base_triangles = 0;
  std::vector<uint64_t> level_vertices;  // L + 1: vertices created at each level (0: base)
  double quant_step = 1.0;       // the coefficient quantizer's unit
  // (L + 1) x 3: step multiplier of (coefficient level f, component c) at
  // index 3f + c; f = 0 is the base residual (x, y, z), f = j >= 1 level j's
  // details (normal, tangent, tangent).
  std::vector<float> scales;
  int top_plane = -1;            // -1: every coefficient is zero
  SrmChunkEntry base;
  std::vector<SrmChunkEntry> flags;     // L: flags of level j's triangles decide level j + 1
  std::vector<SrmChunkEntry> segments;  // (top_plane + 1) x (L + 1), index (top_plane - p)(L + 1) + f

  size_t segment_index(int plane, int f) const {
    return static_cast<size_t>(top_plane - plane) * (levels + 1) + f;
  }
};

// One chunk as found in the file: where it is, what the header declares and
// the bytes actually present (fewer than declared when the file was cut;
// none when the chunk was not loaded).
struct SrmChunk {
  uint64_t offset = 0;
  uint64_t declared = 0;
  uint32_t crc = 0;
  bool loaded = false;
  std::vector<uint8_t> bytes;
  bool complete() const { return loaded && bytes.size() == declared; }
};

struct SrmFile {
  SrmHeader header;
  uint64_t header_size = 0;    // bytes up to the end of the header's checksum
  uint64_t declared_size = 0;  // what the header's table adds up to
  uint64_t file_size = 0;      // bytes present (a prefix may be shorter)
  SrmChunk base;
  std::vector<SrmChunk> flags;
  std::vector<SrmChunk> segments;
};

// The whole file: header, table, then the chunks in table order.
std::vector<uint8_t> write_srm(SrmHeader header, const std::vector<uint8_t>& base,
                               const std::vector<std::vector<uint8_t>>& flags,
                               const std::vector<std::vector<uint8_t>>& segments);

// Which chunks to load: those levels <= max_level need (-1: all), from the
// first `max_bytes` bytes only (0: all).
struct SrmReadOptions {
  int max_level = -1;
  uint64_t max_bytes = 0;
};

// From memory (`size` bytes present). Errors: bad magic, unknown version,
// a cut or corrupt header, a table the header's own limits do not allow.
StatusOr<SrmFile> parse_srm(const uint8_t* data, size_t size, const SrmReadOptions& options = {});
// From a file, reading the header and then only the chunks asked for.
StatusOr<SrmFile> read_srm(const std::string& path, const SrmReadOptions& options = {});

// Checks a complete chunk's checksum ("<what> (bytes a..b) fails its checksum").
Status verify_chunk(const SrmChunk& chunk, bool short_crc, const std::string& what);

}  // namespace srcodec
