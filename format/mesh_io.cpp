#include "format/mesh_io.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <type_traits>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "format/file_io.h"
#include "format/off_reader.h"
#include "format/ply_reader.h"
#include "format/text_numbers.h"

namespace srcodec {
namespace {

namespace fs = std::filesystem;
using OpenMesh::IO::BaseImporter;
using OpenMesh::VertexHandle;
using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::EdgeHandle;

// Records what an OpenMesh reader finds, without OpenMesh's own topology
// checks: its mesh kernel would silently duplicate vertices at non-manifold
// spots, and we want to see (and report) the file as it is.
class SoupImporter final : public BaseImporter {
 public:
  explicit SoupImporter(PolygonMesh* mesh) : mesh_(mesh) {}

  VertexHandle add_vertex(const OpenMesh::Vec3f& p) override { return add_vertex(OpenMesh::Vec3d(p)); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
    mesh_->positions.emplace_back(p[0], p[1], p[2]);
    return VertexHandle(static_cast<int>(mesh_->positions.size()) - 1);
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }

  FaceHandle add_face(const std::vector<VertexHandle>& indices) override {
    std::vector<int32_t> ids(indices.size());
    for (size_t i = 0; i < indices.size(); ++i) ids[i] = indices[i].idx();
    mesh_->add_face(ids.data(), static_cast<int32_t>(ids.size()));
    return FaceHandle(static_cast<int>(mesh_->num_faces()) - 1);
  }
  void set_point(VertexHandle v, const OpenMesh::Vec3f& p) override {
    if (v.idx() >= 0 && static_cast<size_t>(v.idx()) < mesh_->positions.size())
      mesh_->positions[v.idx()] = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  size_t n_vertices() const override { return mesh_->positions.size(); }
  size_t n_faces() const override { return mesh_->num_faces(); }
  size_t n_edges() const override { return 0; }
  bool is_triangle_mesh() const override { return false; }

  // Everything else a reader may hand over (normals, colours, texture
  // coordinates, half-edge connectivity of .om files) is not geometry we code.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  PolygonMesh* mesh_;
};

// OpenMesh writes its complaints to omerr/omlog; we collect them so the one
// error line we print can say what the parser saw, and the terminal stays clean.
class OpenMeshLogCapture {
 public:
  OpenMeshLogCapture() {
    omerr().disconnect(std::cerr);
    omerr().connect(errors_);
    omlog().disable();
    omout().disable();
  }
  ~OpenMeshLogCapture() {
    omerr().flush();
    omerr().disconnect(errors_);
    omerr().connect(std::cerr);
  }
  OpenMeshLogCapture(const OpenMeshLogCapture&) = delete;
  OpenMeshLogCapture& operator=(const OpenMeshLogCapture&) = delete;

  // First line of what the parser said, if anything.
  std::string first_line() const {
    omerr().flush();
    std::string text = errors_.str();
    auto begin = text.find_first_not_of(" \t\r\n");
    if (begin == std::string::npos) return "";
    auto end = text.find_first_of("\r\n", begin);
    return text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  }

 private:
  std::ostringstream errors_;
};

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
  Status checked = check_text_numbers(bytes.value(), ext);
  if (!checked.ok()) return fail(checked);

  PolygonMesh mesh;
  if (ext == ".ply" || ext == ".off") {
    Status s = ext == ".ply" ? read_ply(bytes.value(), &mesh) : read_off(bytes.value(), &mesh);
    if (!s.ok()) return fail(s);
  } else {
    OpenMeshLogCapture capture;
    SoupImporter importer(&mesh);
    OpenMesh::IO::Options options;
    bool read_ok = false;
    try {
      read_ok = OpenMesh::IO::IOManager().read(path, importer, options);
    } catch (const std::exception& e) {
      return fail(parse_error(std::string("the parser failed: ") + e.what()));
    }
    if (!read_ok) {
      std::string said = capture.first_line();
      return fail(parse_error("not a readable " + ext.substr(1) + " file" +
                              (said.empty() ? std::string() : " (parser: " + said + ")")));
    }
  }
  if (mesh.positions.empty()) return fail(parse_error("no vertices found: not a valid " + ext.substr(1) + " file"));
  Status s = validate(mesh);
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

std::string obj_text(const TriangleMesh& mesh) {
  std::string out = "# written by srcodec\n";
  out.reserve(mesh.positions.size() * 40 + mesh.triangles.size() * 24);
  for (const auto& p : mesh.positions) {
    out += "v ";
    append_number(out, p.x());
    out += ' ';
    append_number(out, p.y());
    out += ' ';
    append_number(out, p.z());
    out += '\n';
  }
  for (const auto& t : mesh.triangles) {
    out += "f " + std::to_string(t[0] + 1) + ' ' + std::to_string(t[1] + 1) + ' ' + std::to_string(t[2] + 1) + '\n';
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

}  // namespace

Status write_mesh(const TriangleMesh& mesh, const std::string& path) {
  const std::string ext = file_extension(path);
  std::string bytes;
  if (ext == ".obj") bytes = obj_text(mesh);
  else if (ext == ".ply") bytes = ply_bytes(mesh);
  else return unsupported("cannot write '" + ext + "' meshes (supported: .obj .ply)").with_context(path);
  return write_file_atomically(path, bytes);
}

}  // namespace srcodec
