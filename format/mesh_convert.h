// Between the public srcodec::Mesh (flat arrays, <srcodec/mesh.h>) and the
// TriangleMesh the stages work on.
#pragma once

#include <srcodec/mesh.h>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

Mesh to_public_mesh(const TriangleMesh& mesh);

// Checks what the stages take for granted: whole triples, indices of
// existing vertices, finite coordinates, counts that fit their int32 ids.
// `what` names the mesh in the messages ("the mesh to encode").
StatusOr<TriangleMesh> from_public_mesh(const Mesh& mesh, const std::string& what);

}  // namespace srcodec
