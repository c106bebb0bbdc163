// The C functions srcodec's WebAssembly module exports, over <srcodec/decoder.h>.
// JavaScript (web/src/decoder.js) copies the bytes in, calls one of these,
// and copies the result out: one result is held at a time, until the next
// call or srcodec_release.
#include <srcodec/srcodec.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Result {
  std::vector<float> positions;  // the decoder's doubles, rounded to float32 (WebGL's vertex type)
  std::vector<uint32_t> indices;
  // corner_normals' arrays, when asked for and the mesh has crease edges.
  srcodec::CornerNormals normals;
  std::vector<double> numbers;  // decode's or inspect's scalars, laid out as decoder.js reads them
  std::string message;          // the Status's message when a call failed
};

Result& result() {
  static Result r;
  return r;
}

void release() {
  Result empty;
  std::swap(result(), empty);
}

int fail(const srcodec::Status& status) {
  release();
  result().message = status.message();
  return static_cast<int>(status.code());
}

// JavaScript numbers are doubles: counts up to 2^53 pass exactly, and the
// JavaScript side checks they are whole and non-negative.
uint64_t to_count(double v) { return v <= 0 ? 0 : static_cast<uint64_t>(v); }

}  // namespace

extern "C" {

uint8_t* srcodec_alloc(uint32_t bytes) { return static_cast<uint8_t*>(std::malloc(bytes == 0 ? 1 : bytes)); }
void srcodec_free(uint8_t* p) { std::free(p); }

// Decodes `size` bytes at `data`; 0 on success, else the StatusCode (the
// message is at srcodec_message()). Single-threaded: the same mesh, bit for
// bit, as the native decoder on any number of threads. With `normals` set
// and crease edges in the mesh, also its corner normals (<srcodec/mesh.h>),
// so that the rule that splits them at the creases has one home.
int srcodec_decode(const uint8_t* data, uint32_t size, int level, double max_bytes, double max_vertices, int normals) {
  srcodec::DecodeOptions options;
  options.level = level;
  options.max_bytes = to_count(max_bytes);
  options.max_vertices = to_count(max_vertices);
  options.threads = false;
  srcodec::StatusOr<srcodec::Decoded> decoded = srcodec::decode(data, size, options);
  if (!decoded.ok()) return fail(decoded.status());
  release();
  Result& r = result();
  const srcodec::Mesh& mesh = decoded->mesh;
  if (normals != 0 && !decoded->crease_edges.empty()) {
    srcodec::StatusOr<srcodec::CornerNormals> split = srcodec::corner_normals(mesh, decoded->crease_edges);
    if (!split.ok()) return fail(split.status());
    r.normals = std::move(split).value();
  }
  r.positions.assign(mesh.positions.begin(), mesh.positions.end());
  r.indices = std::move(decoded->mesh.triangles);
  // The scalars, then the crease edges' count and their vertex ids (a few
  // per base mesh: not worth an array export of their own).
  r.numbers = {static_cast<double>(decoded->level), static_cast<double>(decoded->bytes_used),
               static_cast<double>(decoded->last_complete_plane), decoded->base_cut ? 1.0 : 0.0,
               decoded->creases_cut ? 1.0 : 0.0, static_cast<double>(decoded->crease_edges.size() / 2)};
  r.numbers.insert(r.numbers.end(), decoded->crease_edges.begin(), decoded->crease_edges.end());
  return 0;
}

// Reads the header; 0 on success, else the StatusCode. The numbers are the
// FileInfo fields in declaration order, then each level's four fields
// after their count, then each plane's three after theirs.
int srcodec_inspect(const uint8_t* data, uint32_t size) {
  srcodec::StatusOr<srcodec::FileInfo> info = srcodec::inspect(data, size);
  if (!info.ok()) return fail(info.status());
  release();
  const srcodec::FileInfo& f = *info;
  auto n = [](auto v) { return static_cast<double>(v); };
  std::vector<double>& out = result().numbers;
  out = {n(f.version), n(f.file_bytes), n(f.declared_bytes), n(f.header_bytes), n(f.input_vertices),
         n(f.input_triangles), f.bbox_min[0], f.bbox_min[1], f.bbox_min[2], f.bbox_max[0], f.bbox_max[1],
         f.bbox_max[2], f.bits_per_vertex, n(f.base_vertices), n(f.base_triangles), n(f.base_bytes),
         n(f.crease_bytes), n(f.crease_edges), n(f.base_bits), n(f.levels), f.quantizer_step, n(f.top_plane),
         n(f.raw_planes)};
  out.push_back(n(f.level_info.size()));
  for (const auto& l : f.level_info) {
    out.insert(out.end(), {n(l.vertices), n(l.flag_bytes), n(l.coefficient_bytes), n(l.drawable_from)});
  }
  out.push_back(n(f.planes.size()));
  for (const auto& p : f.planes) out.insert(out.end(), {n(p.plane), n(p.bytes), n(p.end)});
  return 0;
}

const float* srcodec_positions() { return result().positions.data(); }
uint32_t srcodec_position_count() { return static_cast<uint32_t>(result().positions.size()); }
const uint32_t* srcodec_indices() { return result().indices.data(); }
uint32_t srcodec_index_count() { return static_cast<uint32_t>(result().indices.size()); }
// The corner normals: 3 floats and a vertex per normal, a normal per index.
const float* srcodec_normals() { return result().normals.normals.data(); }
const uint32_t* srcodec_normal_vertices() { return result().normals.vertices.data(); }
uint32_t srcodec_normal_count() { return static_cast<uint32_t>(result().normals.vertices.size()); }
const uint32_t* srcodec_corners() { return result().normals.corners.data(); }
const double* srcodec_numbers() { return result().numbers.data(); }
uint32_t srcodec_number_count() { return static_cast<uint32_t>(result().numbers.size()); }
const char* srcodec_message() { return result().message.c_str(); }
uint32_t srcodec_message_length() { return static_cast<uint32_t>(result().message.size()); }
void srcodec_release() { release(); }
const char* srcodec_version() { return srcodec::version(); }

}  // extern "C"
