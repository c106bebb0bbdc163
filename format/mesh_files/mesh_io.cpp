#include "format/mesh_files/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <type_traits>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "format/file_io.h"
#include "format/mesh_files/obj_reader.h"
#include "format/mesh_files/off_reader.h"
#include "format/mesh_files/ply_reader.h"
#include "format/mesh_files/stl_reader.h"
#include "format/mesh_files/text_numbers.h"

namespace srcodec {
namespace {

namespace fs = std::filesystem;

Status validate(const PolygonMesh& mesh) {
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!mesh.positions[v].allFinite())
      return parse_error("vertex " + std::to_string(v + 1) + " has a coordinate that is not a finite number (NaN or infinite)");
  }
  if (mesh.num_faces() == 0) {
    return invalid_mesh("has " + std::to_string(mesh.positions.size()) +
                        " vertices but no faces: srcodec needs a surface mesh");
  }
  const auto n = static_cast<int64_t>(mesh.positions.size());
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    if (mesh.face_size(f) < 3)
      return parse_error("face " + std::to_string(f + 1) + " has fewer than 3 corners");
    for (int32_t k = 0; k < mesh.face_size(f); ++k) {
      int32_t v = mesh.face(f)[k];
      if (v < 0 || v >= n) {
        return parse_error("face " + std::to_string(f + 1) + " uses vertex index " +
                           (v < 0 ? std::string("out of range") : std::to_string(int64_t{v} + 1)) +
                           " but the file has " + std::to_string(n) + " vertices");
      }
    }
  }
  return ok_status();
}

}  // namespace

std::string file_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

StatusOr<PolygonMesh> read_polygon_mesh(const std::string& path) {
  const std::string ext = file_extension(path);
  auto fail = [&](const Status& s) { return s.with_context(path); };
  if (ext != ".obj" && ext != ".off" && ext != ".ply" && ext != ".stl") {
    return fail(unsupported("unknown mesh extension '" + ext + "' (supported: .obj .off .ply .stl)"));
  }
  std::error_code ec;
  if (!fs::exists(path, ec)) return fail(not_found("no such file"));
  if (!fs::is_regular_file(path, ec)) return fail(io_error("not a regular file"));
  const auto size = fs::file_size(path, ec);
  if (ec) return fail(io_error("cannot read: " + ec.message()));
  if (size == 0) return fail(parse_error("file is empty (0 bytes)"));
  auto bytes = read_file_bytes(path);
  if (!bytes.ok()) return bytes.status();  // already names the file
  PolygonMesh mesh;
  Status s;
  if (ext == ".obj") s = read_obj(bytes.value(), &mesh);
  else if (ext == ".off") s = read_off(bytes.value(), &mesh);
  else if (ext == ".stl") s = read_stl(bytes.value(), &mesh);
  else if (s = check_ascii_ply_numbers(bytes.value()); s.ok()) s = read_ply(bytes.value(), &mesh);
  if (!s.ok()) return fail(s);
  if (mesh.positions.empty()) return fail(parse_error("no vertices found: not a valid " + ext.substr(1) + " file"));
  s = validate(mesh);
  if (!s.ok()) return fail(s);
  return mesh;
}

StatusOr<TriangleMesh> read_triangle_mesh(const std::string& path, CleanReport* report) {
  SRCODEC_ASSIGN_OR_RETURN(PolygonMesh raw, read_polygon_mesh(path));
  TriangleMesh mesh = clean_mesh(raw, report);
  if (mesh.triangles.empty()) {
    return invalid_mesh("every face is degenerate (zero area or repeated corners)").with_context(path);
  }
  return mesh;
}

namespace {

// Shortest text that reads back to the same value: as a float when the
// value is one (most meshes come from float files), else as a double.
void append_number(std::string& out, double value) {
  char buffer[64];
  std::to_chars_result r;
  const auto as_float = static_cast<float>(value);
  if (static_cast<double>(as_float) == value) {
    r = std::to_chars(buffer, buffer + sizeof buffer, as_float);
  } else {
    r = std::to_chars(buffer, buffer + sizeof buffer, value);
  }
  out.append(buffer, r.ptr);
}

// `tag` and three numbers on a line.
template <typename Point>
void append_point(std::string& out, const char* tag, const Point& p) {
  out += tag;
  append_number(out, p.x());
  out += ' ';
  append_number(out, p.y());
  out += ' ';
  append_number(out, p.z());
  out += '\n';
}

// One line per vertex (`vertex_tag` and three numbers), then one per
// triangle (`face_tag` and three indices counted from `first_index`): the
// body of OBJ and OFF files.
void append_text_mesh(std::string& out, const TriangleMesh& mesh, const char* vertex_tag, const char* face_tag,
                      int32_t first_index) {
  out.reserve(out.size() + mesh.positions.size() * 40 + mesh.triangles.size() * 24);
  for (const auto& p : mesh.positions) append_point(out, vertex_tag, p);
  for (const auto& t : mesh.triangles) {
    out += face_tag + std::to_string(t[0] + first_index) + ' ' + std::to_string(t[1] + first_index) + ' ' +
           std::to_string(t[2] + first_index) + '\n';
  }
}

// With normals: the vertices, a `vn` line per normal (floats, written as
// such), and each corner as `v//vn`.
std::string obj_text(const TriangleMesh& mesh, const SectorNormals* normals) {
  std::string out = "# written by srcodec\n";
  if (normals == nullptr) {
    append_text_mesh(out, mesh, "v ", "f ", 1);
    return out;
  }
  out.reserve(out.size() + mesh.positions.size() * 40 + normals->normals.size() * 36 + mesh.triangles.size() * 40);
  for (const auto& p : mesh.positions) append_point(out, "v ", p);
  for (const auto& n : normals->normals) append_point(out, "vn ", n.cast<double>());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    out += 'f';
    for (int k = 0; k < 3; ++k)
      out += ' ' + std::to_string(mesh.triangles[t][k] + 1) + "//" + std::to_string(normals->corners[t][k] + 1);
    out += '\n';
  }
  return out;
}

template <typename T>
void append_le(std::string& out, T value) {
  static_assert(std::is_trivially_copyable_v<T>);
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));  // x86 and ARM Linux are little-endian
}

std::string ply_bytes(const TriangleMesh& mesh) {
  const bool fits_float = std::all_of(mesh.positions.begin(), mesh.positions.end(), [](const Eigen::Vector3d& p) {
    return p.cast<float>().cast<double>() == p;
  });
  const char* type = fits_float ? "float" : "double";
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by srcodec\n";
  out += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  out += std::string("property ") + type + " x\nproperty " + type + " y\nproperty " + type + " z\n";
  out += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  for (const auto& p : mesh.positions) {
    for (int k = 0; k < 3; ++k) {
      if (fits_float) append_le(out, static_cast<float>(p[k]));
      else append_le(out, p[k]);
    }
  }
  for (const auto& t : mesh.triangles) {
    append_le(out, uint8_t{3});
    for (int k = 0; k < 3; ++k) append_le(out, int32_t{t[k]});
  }
  return out;
}

std::string off_text(const TriangleMesh& mesh) {
  std::string out = "OFF\n# written by srcodec\n" + std::to_string(mesh.positions.size()) + " " +
                    std::to_string(mesh.triangles.size()) + " 0\n";
  append_text_mesh(out, mesh, "", "3 ", 0);
  return out;
}

// Binary STL: float corners, each triangle with its unit normal.
std::string stl_bytes(const TriangleMesh& mesh) {
  std::string out = "binary STL written by srcodec";
  out.resize(80, ' ');
  append_le(out, static_cast<uint32_t>(mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.positions[t[0]];
    const Eigen::Vector3d n = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).normalized();
    for (int k = 0; k < 3; ++k) append_le(out, std::isfinite(n[k]) ? static_cast<float>(n[k]) : 0.0f);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) append_le(out, static_cast<float>(mesh.positions[t[c]][k]));
    append_le(out, uint16_t{0});
  }
  return out;
}

}  // namespace

bool keeps_corner_normals(const std::string& path) { return file_extension(path) == ".obj"; }

Status write_mesh(const TriangleMesh& mesh, const std::string& path, const SectorNormals* normals) {
  const std::string ext = file_extension(path);
  std::string bytes;
  if (ext == ".obj") bytes = obj_text(mesh, normals);
  else if (ext == ".ply") bytes = ply_bytes(mesh);
  else if (ext == ".off") bytes = off_text(mesh);
  else if (ext == ".stl") bytes = stl_bytes(mesh);
  else return unsupported("cannot write '" + ext + "' meshes (supported: .obj .ply .off .stl)").with_context(path);
  return write_file_atomically(path, bytes);
}

}  // namespace srcodec
