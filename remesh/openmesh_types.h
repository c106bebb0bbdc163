// OpenMesh's triangle mesh with double-precision points, as the remesher's
// stages that use OpenMesh (oversampling, collapses) need it.
#pragma once

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

namespace srcodec {

struct OmDoubleTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using OmMesh = OpenMesh::TriMesh_ArrayKernelT<OmDoubleTraits>;

}  // namespace srcodec
