#include "format/srm/srm_file.h"

#include <cmath>
#include <fstream>
#include <functional>

#include "format/byte_io.h"
#include "format/checksum.h"

namespace srcodec {
namespace {

constexpr uint8_t kMagic[4] = {0x89, 'S', 'R', 'M'};
constexpr size_t kPreambleSize = 10;                 // magic, version, reserved, body size
constexpr uint32_t kMaxBodySize = 1u << 24;           // far above any real table
constexpr uint64_t kMaxChunkLength = uint64_t{1} << 40;

void write_body(const SrmHeader& h, ByteWriter& w) {
  w.varint(h.input_vertices);
  w.varint(h.input_triangles);
  for (int i = 0; i < 3; ++i) w.f32(static_cast<float>(h.bbox_min[i]));
  for (int i = 0; i < 3; ++i) w.f32(static_cast<float>(h.bbox_max[i]));
  w.u8(static_cast<uint8_t>(h.levels));
  w.u8(static_cast<uint8_t>(h.base_bits));
  w.f32(static_cast<float>(h.grid_step));
  w.varint(h.base_vertices);
  w.varint(h.base_triangles);
  for (uint64_t n : h.level_vertices) w.varint(n);
  w.f32(static_cast<float>(h.quant_step));
  w.f32(static_cast<float>(h.tangential_factor));
  w.u8(static_cast<uint8_t>(h.top_plane + 1));
  if (h.version() >= 2) w.u8(static_cast<uint8_t>(h.raw_planes));
  w.varint(h.base.length);
  w.u32(h.base.crc);
  if (h.has_creases) {
    w.varint(h.creases.length);
    w.u32(h.creases.crc);
  }
  for (const SrmChunkEntry& e : h.flags) {
    w.varint(e.length);
    w.u32(e.crc);
  }
  w.varint(h.segments.size());
  for (const SrmChunkEntry& e : h.segments) {
    w.varint(e.length);
    if (e.length > 0) w.u16(static_cast<uint16_t>(e.crc));
  }
}

bool read_f32(ByteReader& r, double& v) {
  float f = 0;
  if (!r.f32(f)) return false;
  v = f;
  return true;
}

bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }

// Fields in the order write_body writes them; every value is checked against
// the limits the format allows before anything is sized from it.
Status read_counts_and_geometry(ByteReader& r, SrmHeader& h) {
  uint8_t levels = 0, bits = 0;
  bool ok = r.varint(h.input_vertices) && r.varint(h.input_triangles);
  for (int i = 0; ok && i < 3; ++i) ok = read_f32(r, h.bbox_min[i]);
  for (int i = 0; ok && i < 3; ++i) ok = read_f32(r, h.bbox_max[i]);
  ok = ok && r.u8(levels) && r.u8(bits) && read_f32(r, h.grid_step) && r.varint(h.base_vertices) &&
       r.varint(h.base_triangles);
  if (!ok) return r.error("header", "the header ends early");
  if (levels > kSrmMaxLevels)
    return r.error("header", "levels is " + std::to_string(levels) + ", above " + std::to_string(kSrmMaxLevels));
  if (bits < 1 || bits > 24) return r.error("header", "base position bits is " + std::to_string(bits) + ", not 1..24");
  if (!finite_positive(h.grid_step)) return r.error("header", "the base grid step is not a positive number");
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(h.bbox_min[i]) || !std::isfinite(h.bbox_max[i]) || h.bbox_min[i] > h.bbox_max[i])
      return r.error("header", "the bounding box is not finite or has min > max");
  h.levels = levels;
  h.base_bits = bits;
  h.level_vertices.assign(h.levels + 1, 0);
  for (uint64_t& n : h.level_vertices)
    if (!r.varint(n)) return r.error("header", "the level table ends early");
  if (h.level_vertices[0] != h.base_vertices)
    return r.error("header", "level 0 has " + std::to_string(h.level_vertices[0]) + " vertices but the base mesh " +
                                 std::to_string(h.base_vertices));
  return ok_status();
}

Status read_quantization(ByteReader& r, int version, SrmHeader& h) {
  if (!read_f32(r, h.quant_step) || !read_f32(r, h.tangential_factor))
    return r.error("header", "the header ends early");
  if (!finite_positive(h.quant_step)) return r.error("header", "the quantizer step is not a positive number");
  if (!finite_positive(h.tangential_factor))
    return r.error("header", "the tangential step factor is not a positive number");
  uint8_t top = 0;
  if (!r.u8(top)) return r.error("header", "the header ends early");
  if (top > kSrmMaxPlane + 1)
    return r.error("header", "the top bit plane is " + std::to_string(top - 1) + ", above " +
                                 std::to_string(kSrmMaxPlane));
  h.top_plane = top - 1;
  h.raw_planes = 0;
  if (version >= 2) {
    // Version 2 exists for its raw planes; version 3 may have none.
    const int least = version == 2 ? 1 : 0;
    uint8_t raw = 0;
    if (!r.u8(raw)) return r.error("header", "the header ends early");
    if (raw < least || raw > kSrmMaxPlane + 1)
      return r.error("header", std::to_string(raw) + " raw planes, not " + std::to_string(least) + ".." +
                                   std::to_string(kSrmMaxPlane + 1) +
                                   (version == 2 ? " (version 2 has at least one)" : ""));
    h.raw_planes = raw;
  }
  return ok_status();
}

Status read_entry(ByteReader& r, SrmChunkEntry& e, bool short_crc, const char* what) {
  bool ok = r.varint(e.length);
  if (ok && short_crc && e.length > 0) {
    uint16_t c = 0;
    ok = r.u16(c);
    e.crc = c;
  } else if (ok && !short_crc) {
    ok = r.u32(e.crc);
  }
  if (!ok) return r.error("chunk table", std::string("the entry of ") + what + " ends early");
  if (e.length > kMaxChunkLength) return r.error("chunk table", std::string(what) + " is impossibly long");
  return ok_status();
}

Status read_table(ByteReader& r, int version, SrmHeader& h) {
  SRCODEC_RETURN_IF_ERROR(read_entry(r, h.base, false, "the base mesh"));
  h.has_creases = version >= 3;
  if (h.has_creases) SRCODEC_RETURN_IF_ERROR(read_entry(r, h.creases, false, "the creases"));
  h.flags.resize(h.levels);
  for (SrmChunkEntry& e : h.flags) SRCODEC_RETURN_IF_ERROR(read_entry(r, e, false, "a flag chunk"));
  uint64_t count = 0;
  if (!r.varint(count)) return r.error("chunk table", "the segment count ends early");
  if (count > h.segment_count())
    return r.error("chunk table", std::to_string(count) + " segments listed; " + std::to_string(h.top_plane + 1) +
                                      " planes of " + std::to_string(h.levels + 1) + " levels have " +
                                      std::to_string(h.segment_count()));
  // Each entry takes at least one byte, so the count is bounded by what is left.
  if (count > r.remaining()) return r.error("chunk table", "it lists more segments than it has bytes for");
  h.segments.resize(count);
  for (SrmChunkEntry& e : h.segments) SRCODEC_RETURN_IF_ERROR(read_entry(r, e, true, "a segment"));
  if (r.remaining() != 0) return r.error("header", std::to_string(r.remaining()) + " unexpected bytes at its end");
  return ok_status();
}

// The header from the first bytes of a file; `have` bytes are present and
// `total` would be (a cut file: have == total). Returns the header's size.
StatusOr<uint64_t> parse_header(const uint8_t* data, size_t have, SrmHeader& h) {
  if (have < kPreambleSize)
    return parse_error("the file has " + std::to_string(have) + " bytes, fewer than the " +
                       std::to_string(kPreambleSize) + " an .srm header starts with");
  for (int i = 0; i < 4; ++i)
    if (data[i] != kMagic[i]) return parse_error("not an .srm file (its first bytes are not \\x89SRM)");
  if (data[4] < kSrmOldestVersion || data[4] > kSrmVersion)
    return unsupported(".srm version " + std::to_string(data[4]) + "; this srcodec reads versions " +
                       std::to_string(kSrmOldestVersion) + " to " + std::to_string(kSrmVersion));
  ByteReader pre(data + 6, 4, 6);
  uint32_t body = 0;
  (void)pre.u32(body);
  if (body > kMaxBodySize) return parse_error("header at byte 6: a header of " + std::to_string(body) + " bytes");
  const uint64_t header_size = kPreambleSize + uint64_t{body} + 4;
  if (have < header_size)
    return parse_error("the file ends at byte " + std::to_string(have) + ", inside its " +
                       std::to_string(header_size) + "-byte header: nothing can be decoded before byte " +
                       std::to_string(header_size));
  ByteReader crc_reader(data + kPreambleSize + body, 4, kPreambleSize + body);
  uint32_t stored = 0;
  (void)crc_reader.u32(stored);
  if (crc32(data, kPreambleSize + body) != stored)
    return parse_error("the header (bytes 0.." + std::to_string(header_size - 1) +
                       ") fails its checksum: the file is corrupt");
  ByteReader r(data + kPreambleSize, body, kPreambleSize);
  SRCODEC_RETURN_IF_ERROR(read_counts_and_geometry(r, h));
  SRCODEC_RETURN_IF_ERROR(read_quantization(r, data[4], h));
  SRCODEC_RETURN_IF_ERROR(read_table(r, data[4], h));
  return header_size;
}

// Fills the chunk list from the table; `load` copies the present bytes of
// the chunks asked for.
Status lay_out(SrmFile& f, const SrmReadOptions& options,
               const std::function<Status(SrmChunk&)>& load) {
  const SrmHeader& h = f.header;
  uint64_t offset = f.header_size;
  auto place = [&](SrmChunk& c, const SrmChunkEntry& e) {
    c.offset = offset;
    c.declared = e.length;
    c.crc = e.crc;
    offset += e.length;
  };
  place(f.base, h.base);
  if (h.has_creases) place(f.creases, h.creases);
  f.flags.resize(h.flags.size());
  for (size_t j = 0; j < h.flags.size(); ++j) place(f.flags[j], h.flags[j]);
  f.segments.resize(h.segments.size());
  for (size_t s = 0; s < h.segments.size(); ++s) place(f.segments[s], h.segments[s]);
  f.declared_size = offset;
  if (f.file_size > f.declared_size)
    return parse_error("the file has " + std::to_string(f.file_size - f.declared_size) + " bytes after its last chunk "
                       "(which ends at byte " + std::to_string(f.declared_size) + "): damaged or not written by srcodec");
  const int max_level = options.max_level < 0 ? h.levels : std::min(options.max_level, h.levels);
  SRCODEC_RETURN_IF_ERROR(load(f.base));
  // Every level needs the creases: the wavelet's rules follow them.
  if (h.has_creases) SRCODEC_RETURN_IF_ERROR(load(f.creases));
  for (int j = 0; j < max_level; ++j) SRCODEC_RETURN_IF_ERROR(load(f.flags[j]));
  for (size_t s = 0; s < f.segments.size(); ++s)
    if (static_cast<int>(s % (h.levels + 1)) <= max_level) SRCODEC_RETURN_IF_ERROR(load(f.segments[s]));
  return ok_status();
}

uint64_t present(const SrmChunk& c, uint64_t file_size) {
  if (c.offset >= file_size) return 0;
  return std::min(c.declared, file_size - c.offset);
}

}  // namespace

std::vector<uint8_t> write_srm(SrmHeader header, const std::vector<uint8_t>& base,
                               const std::vector<std::vector<uint8_t>>& flags,
                               const std::vector<std::vector<uint8_t>>& segments,
                               const std::vector<uint8_t>& creases) {
  header.base = {base.size(), crc32(base.data(), base.size())};
  header.has_creases = header.has_creases || !creases.empty();
  header.creases = header.has_creases ? SrmChunkEntry{creases.size(), crc32(creases.data(), creases.size())}
                                      : SrmChunkEntry{};
  header.flags.clear();
  for (const auto& c : flags) header.flags.push_back({c.size(), crc32(c.data(), c.size())});
  header.segments.clear();
  for (const auto& c : segments) header.segments.push_back({c.size(), crc16_of(c.data(), c.size())});
  ByteWriter body;
  write_body(header, body);
  ByteWriter w;
  for (uint8_t m : kMagic) w.u8(m);
  w.u8(static_cast<uint8_t>(header.version()));
  w.u8(0);
  w.u32(static_cast<uint32_t>(body.size()));
  w.bytes(body.data());
  w.u32(crc32(w.data().data(), w.size()));
  w.bytes(base);
  if (header.has_creases) w.bytes(creases);
  for (const auto& c : flags) w.bytes(c);
  for (const auto& c : segments) w.bytes(c);
  return std::move(w.data());
}

StatusOr<SrmFile> parse_srm(const uint8_t* data, size_t size, const SrmReadOptions& options) {
  SrmFile f;
  f.file_size = options.max_bytes > 0 ? std::min<uint64_t>(size, options.max_bytes) : size;
  StatusOr<uint64_t> header_size = parse_header(data, f.file_size, f.header);
  if (!header_size.ok()) return header_size.status();
  f.header_size = header_size.value();
  SRCODEC_RETURN_IF_ERROR(lay_out(f, options, [&](SrmChunk& c) {
    const uint64_t n = present(c, f.file_size);
    c.bytes.assign(data + (n ? c.offset : 0), data + (n ? c.offset + n : 0));
    c.loaded = true;
    return ok_status();
  }));
  return f;
}

StatusOr<SrmFile> read_srm(const std::string& path, const SrmReadOptions& options) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return not_found(path + ": cannot open");
  const uint64_t size = static_cast<uint64_t>(in.tellg());
  SrmFile f;
  f.file_size = options.max_bytes > 0 ? std::min(size, options.max_bytes) : size;
  // The header: the preamble says how long it is.
  std::vector<uint8_t> head(std::min<uint64_t>(f.file_size, kPreambleSize));
  in.seekg(0);
  in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(head.size()));
  if (head.size() == kPreambleSize) {
    const uint64_t body = head[6] | (uint32_t{head[7]} << 8) | (uint32_t{head[8]} << 16) | (uint32_t{head[9]} << 24);
    const uint64_t want = std::min<uint64_t>(f.file_size, kPreambleSize + std::min<uint64_t>(body, kMaxBodySize) + 4);
    head.resize(want);
    in.seekg(0);
    in.read(reinterpret_cast<char*>(head.data()), static_cast<std::streamsize>(want));
  }
  if (!in) return io_error(path + ": read failed");
  StatusOr<uint64_t> header_size = parse_header(head.data(), head.size(), f.header);
  if (!header_size.ok()) return header_size.status().with_context(path);
  f.header_size = header_size.value();
  Status status = lay_out(f, options, [&](SrmChunk& c) {
    const uint64_t n = present(c, f.file_size);
    c.bytes.resize(n);
    c.loaded = true;
    if (n == 0) return ok_status();
    in.seekg(static_cast<std::streamoff>(c.offset));
    in.read(reinterpret_cast<char*>(c.bytes.data()), static_cast<std::streamsize>(n));
    return in ? ok_status() : io_error("read failed at byte " + std::to_string(c.offset));
  });
  if (!status.ok()) return status.with_context(path);
  return f;
}

StatusOr<std::vector<uint8_t>> truncate_srm(const uint8_t* data, size_t size, uint64_t segment_bytes) {
  SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(data, size));
  std::vector<std::vector<uint8_t>> flags, segments;
  if (!f.base.complete()) return invalid_argument("truncate: the file is already cut inside its base mesh");
  if (f.header.has_creases && !f.creases.complete())
    return invalid_argument("truncate: the file is already cut inside its creases");
  for (const SrmChunk& c : f.flags) {
    if (!c.complete()) return invalid_argument("truncate: the file is already cut inside its flags");
    flags.push_back(c.bytes);
  }
  uint64_t left = segment_bytes;
  for (const SrmChunk& c : f.segments) {
    if (left == 0) break;
    const uint64_t take = std::min<uint64_t>(left, c.bytes.size());
    segments.emplace_back(c.bytes.begin(), c.bytes.begin() + static_cast<std::ptrdiff_t>(take));
    left -= take;
    if (take < c.declared) break;  // cut inside (or a chunk the input itself had cut)
  }
  return write_srm(f.header, f.base.bytes, flags, segments, f.creases.bytes);
}

StatusOr<std::vector<uint8_t>> truncate_srm_to_size(const uint8_t* data, size_t size, uint64_t bytes) {
  SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(data, size));
  uint64_t lo = 0, hi = 0;
  for (const SrmChunk& c : f.segments) hi += c.bytes.size();
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> smallest, truncate_srm(data, size, 0));
  if (smallest.size() > bytes)
    return invalid_argument(std::to_string(bytes) + " bytes cannot hold the file's header, base mesh" +
                            (f.header.has_creases ? ", creases" : "") + " and refinement flags, which take " +
                            std::to_string(smallest.size()));
  while (lo < hi) {
    const uint64_t mid = lo + (hi - lo + 1) / 2;
    SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, truncate_srm(data, size, mid));
    if (file.size() <= bytes) {
      lo = mid;
    } else {
      hi = mid - 1;
    }
  }
  return truncate_srm(data, size, lo);
}

Status verify_chunk(const SrmChunk& chunk, bool short_crc, const std::string& what) {
  if (!chunk.complete()) return ok_status();
  uint32_t crc = crc32(chunk.bytes.data(), chunk.bytes.size());
  if (short_crc) crc &= 0xffffu;
  if (crc == chunk.crc) return ok_status();
  return parse_error(what + " (bytes " + std::to_string(chunk.offset) + ".." +
                     std::to_string(chunk.offset + chunk.declared - 1) + ") fails its checksum: the file is corrupt");
}

}  // namespace srcodec
