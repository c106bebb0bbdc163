// The .srm container, versions 1 to 3 (byte layout: format/srm/README.md): a
// header with counts, bounding box, quantization and the table of every
// chunk's length and checksum, then the base mesh chunk, the crease chunk
// (version 3), one refinement-flag chunk per level, and the coefficient
// segments in embedded order (bit-plane major, level minor). Any prefix that
// holds the whole header parses: chunks past the cut are missing or partial,
// and the decoder makes the best mesh of them.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "format/status.h"

namespace srcodec {

// The newest version this srcodec reads and writes. Version 2 adds raw
// planes (SrmHeader::raw_planes), version 3 the crease chunk
// (SrmHeader::has_creases); a file is written in the oldest version that
// holds what it has, so a file without creases is one every reader of
// versions 1 and 2 decodes.
inline constexpr uint8_t kSrmVersion = 3;
inline constexpr uint8_t kSrmOldestVersion = 1;
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
  // The original mesh's bounding box (PSNR reference, base grid origin).
  // Stored as f32: the encoder rounds it (and both steps) to float first.
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero(), bbox_max = Eigen::Vector3d::Zero();
  int levels = 0;                // finest level L, 0..kSrmMaxLevels
  int base_bits = 12;            // base position grid: bits per coordinate
  double grid_step = 1.0;        // grid spacing; origin bbox_min
  uint64_t base_vertices = 0, base_triangles = 0;
  std::vector<uint64_t> level_vertices;  // L + 1: vertices created at each level (0: base)
  double quant_step = 1.0;       // the coefficient quantizer's unit
  // Tangential detail components' step relative to normal ones.
  double tangential_factor = 1.0;
  int top_plane = -1;            // -1: every coefficient is zero
  // The segments of planes below this hold raw bits, not an arithmetic-coded
  // stream (codec/bitplane_model.h). 0..31; version 1 has none, version 2
  // at least one.
  int raw_planes = 0;
  // The file has a crease chunk (version 3): one flag per base edge saying
  // whether the surface is sharp along it (codec/crease_coder.h).
  bool has_creases = false;
  SrmChunkEntry base;
  SrmChunkEntry creases;                // with has_creases only
  std::vector<SrmChunkEntry> flags;     // L: flags of level j's triangles decide level j + 1
  // The segments present, in stream order: (top_plane + 1) x (L + 1) in a
  // whole file, fewer in a file cut by the encoder's rate control.
  std::vector<SrmChunkEntry> segments;

  // The version write_srm writes: 3 with creases, else 2 with raw planes,
  // else 1.
  int version() const { return has_creases ? 3 : raw_planes > 0 ? 2 : 1; }
  size_t segment_count() const { return static_cast<size_t>(top_plane + 1) * (levels + 1); }
  size_t segment_index(int plane, int f) const {
    return static_cast<size_t>(top_plane - plane) * (levels + 1) + f;
  }
  // Step multiplier of coefficient level f (0: base residual, j >= 1: level
  // j's details) and component c (details: 0 normal, 1-2 tangents). A
  // level-f coefficient moves an area ~4^-f of the surface, so for the L2
  // error to cost the same per bit everywhere its step grows as 2^f.
  double scale(int f, int c) const {
    const double normal = std::ldexp(1.0, f - levels);
    return (f > 0 && c > 0) ? normal * tangential_factor : normal;
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
  SrmChunk creases;  // without header.has_creases: none (declared 0, not loaded)
  std::vector<SrmChunk> flags;
  std::vector<SrmChunk> segments;  // as many as the table lists; decoding stops after the last
};

// The whole file: header, table, then the chunks in table order. The crease
// chunk is written when `creases` is not empty or header.has_creases asks
// for it (version 3); a file without creases has none, and its bytes are
// those of version 1 or 2.
std::vector<uint8_t> write_srm(SrmHeader header, const std::vector<uint8_t>& base,
                               const std::vector<std::vector<uint8_t>>& flags,
                               const std::vector<std::vector<uint8_t>>& segments,
                               const std::vector<uint8_t>& creases = {});

// The file with only the first `segment_bytes` bytes of its coefficient
// segments (the last one cut short where the count ends inside it), and a
// table that lists just those: what rate control writes. Decodes like the
// whole file's prefix with as many segment bytes.
StatusOr<std::vector<uint8_t>> truncate_srm(const uint8_t* data, size_t size, uint64_t segment_bytes);
inline StatusOr<std::vector<uint8_t>> truncate_srm(const std::vector<uint8_t>& file, uint64_t segment_bytes) {
  return truncate_srm(file.data(), file.size(), segment_bytes);
}

// The largest file truncate_srm makes of at most `bytes` bytes: its table
// shrinks with the segments it lists, so the segment bytes that fit are
// searched for, not subtracted. An error when even the header, base mesh,
// creases and flags alone take more.
StatusOr<std::vector<uint8_t>> truncate_srm_to_size(const uint8_t* data, size_t size, uint64_t bytes);

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
