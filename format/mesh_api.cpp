// <srcodec/mesh.h>: mesh files, over format/mesh_files/.
#include <string>

#include "format/crease_normals.h"
#include "format/mesh_convert.h"
#include "format/mesh_files/mesh_io.h"

namespace srcodec {

StatusOr<Mesh> read_mesh(const std::string& path) {
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh mesh, read_triangle_mesh(path));
  return to_public_mesh(mesh);
}

Status write_mesh(const std::string& path, const Mesh& mesh) {
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh m, from_public_mesh(mesh, "the mesh to write to " + path));
  return write_mesh(m, path);
}

Status write_mesh(const std::string& path, const Mesh& mesh, const std::vector<uint32_t>& crease_edges) {
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh m, from_public_mesh(mesh, "the mesh to write to " + path));
  SRCODEC_ASSIGN_OR_RETURN(const auto creases, crease_pairs(crease_edges, m.positions.size()));
  if (creases.empty() || !keeps_corner_normals(path)) return write_mesh(m, path);
  const SectorNormals normals = crease_normals(m, creases);
  return write_mesh(m, path, &normals);
}

}  // namespace srcodec
