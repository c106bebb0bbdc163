// <srcodec/mesh.h>: mesh files, over format/mesh_files/.
#include <string>

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

}  // namespace srcodec
