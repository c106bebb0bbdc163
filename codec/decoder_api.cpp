// <srcodec/decoder.h>: decode, inspect and truncate over the container
// (format/srm/) and the codec (codec/srm_codec.h).
#include <srcodec/decoder.h>
#include <srcodec/srcodec.h>

#include <algorithm>
#include <string>

#include "codec/srm_codec.h"
#include "format/mesh_convert.h"
#include "format/srm/srm_file.h"

namespace srcodec {
namespace {

// The highest vertex limit DecodeOptions allows: vertex ids are int32.
constexpr uint64_t kMaxVerticesLimit = uint64_t{1} << 31;

Status check_bytes(const uint8_t* data, size_t size) {
  if (data == nullptr && size > 0) return invalid_argument("no data: a null pointer with " + std::to_string(size) +
                                                           " bytes");
  if (size == 0) return parse_error("no bytes: an .srm file starts with its header");
  return ok_status();
}

Status check_options(const DecodeOptions& o) {
  if (o.level < -1 || o.level > kSrmMaxLevels)
    return invalid_argument("level " + std::to_string(o.level) + ": use -1 (the finest) or 0.." +
                            std::to_string(kSrmMaxLevels));
  if (o.max_vertices < 1 || o.max_vertices > kMaxVerticesLimit)
    return invalid_argument("max_vertices " + std::to_string(o.max_vertices) + ": use 1.." +
                            std::to_string(kMaxVerticesLimit));
  return ok_status();
}

// How many base edges the crease chunk marks: decoding it needs the base
// mesh's triangles. -1 when the two are not both whole or do not decode
// (inspect reports, decode is the one to say what is wrong).
int64_t crease_count(const SrmFile& f) {
  if (!f.header.has_creases) return 0;
  if (!f.base.complete() || !f.creases.complete()) return -1;
  const StatusOr<std::vector<std::array<int32_t, 2>>> creases = decode_srm_creases(f);
  return creases.ok() ? static_cast<int64_t>(creases->size()) : -1;
}

}  // namespace

const char* version() { return SRCODEC_VERSION; }

StatusOr<Decoded> decode(const uint8_t* data, size_t size, const DecodeOptions& options) {
  SRCODEC_RETURN_IF_ERROR(check_options(options));
  SRCODEC_RETURN_IF_ERROR(check_bytes(data, size));
  SrmReadOptions read;
  read.max_level = options.level;
  read.max_bytes = options.max_bytes;
  SRCODEC_ASSIGN_OR_RETURN(const SrmFile file, parse_srm(data, size, read));
  if (options.level > file.header.levels)
    return invalid_argument("level " + std::to_string(options.level) + ": the file has levels 0.." +
                            std::to_string(file.header.levels));
  SrmDecodeOptions decode_options;
  decode_options.level = options.level;
  decode_options.max_vertices = options.max_vertices;
  decode_options.threads = options.threads;
  SRCODEC_ASSIGN_OR_RETURN(DecodedSrm decoded, decode_srm(file, decode_options));
  Decoded out;
  out.mesh = to_public_mesh(decoded.mesh);
  out.level = decoded.level;
  out.bytes_used = decoded.bytes_used;
  out.last_complete_plane = decoded.last_plane;
  out.base_cut = decoded.base_cut;
  out.creases_cut = decoded.creases_cut;
  out.crease_edges.reserve(2 * decoded.crease_edges.size());
  for (const auto& e : decoded.crease_edges)
    out.crease_edges.insert(out.crease_edges.end(), {static_cast<uint32_t>(e[0]), static_cast<uint32_t>(e[1])});
  return out;
}

StatusOr<FileInfo> inspect(const uint8_t* data, size_t size) {
  SRCODEC_RETURN_IF_ERROR(check_bytes(data, size));
  SrmReadOptions read;
  read.max_level = 0;  // the header's table says it all
  SRCODEC_ASSIGN_OR_RETURN(const SrmFile f, parse_srm(data, size, read));
  const SrmHeader& h = f.header;
  FileInfo info;
  info.version = h.version();
  info.file_bytes = f.file_size;
  info.declared_bytes = f.declared_size;
  info.header_bytes = f.header_size;
  info.input_vertices = h.input_vertices;
  info.input_triangles = h.input_triangles;
  for (int k = 0; k < 3; ++k) {
    info.bbox_min[k] = h.bbox_min[k];
    info.bbox_max[k] = h.bbox_max[k];
  }
  info.bits_per_vertex = 8.0 * static_cast<double>(f.file_size) /
                         static_cast<double>(std::max<uint64_t>(h.input_vertices, 1));
  info.base_vertices = h.base_vertices;
  info.base_triangles = h.base_triangles;
  info.base_bytes = h.base.length;
  info.crease_bytes = h.has_creases ? h.creases.length : 0;
  info.crease_edges = crease_count(f);
  info.base_bits = h.base_bits;
  info.levels = h.levels;
  info.quantizer_step = h.quant_step;
  info.top_plane = h.top_plane;
  info.raw_planes = h.raw_planes;

  info.level_info.resize(static_cast<size_t>(h.levels) + 1);
  uint64_t vertices = 0;
  for (int l = 0; l <= h.levels; ++l) {
    FileInfo::Level& level = info.level_info[l];
    vertices += h.level_vertices[l];
    level.vertices = vertices;
    level.flag_bytes = l > 0 ? h.flags[l - 1].length : 0;
    const SrmChunk& last = l > 0 ? f.flags[l - 1] : f.base;
    level.drawable_from = last.offset + last.declared;
  }
  // Segments are plane-major, level-minor; a rate-controlled file's table
  // ends where the encoder cut the stream.
  for (int p = h.top_plane; p >= 0; --p) {
    FileInfo::Plane plane;
    plane.plane = p;
    plane.end = info.planes.empty() ? info.level_info.back().drawable_from : info.planes.back().end;
    for (int l = 0; l <= h.levels; ++l) {
      const size_t index = h.segment_index(p, l);
      if (index >= f.segments.size()) break;
      const SrmChunk& c = f.segments[index];
      info.level_info[l].coefficient_bytes += c.declared;
      plane.bytes += c.declared;
      plane.end = c.offset + c.declared;
    }
    info.planes.push_back(plane);
  }
  return info;
}

StatusOr<std::vector<uint8_t>> truncate(const uint8_t* data, size_t size, uint64_t bytes) {
  SRCODEC_RETURN_IF_ERROR(check_bytes(data, size));
  return truncate_srm_to_size(data, size, bytes);
}

}  // namespace srcodec
