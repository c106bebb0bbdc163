// Oversampling by Butterfly or Loop subdivision (paper §IV). OpenMesh's
// uniform subdividers do the work; this file converts meshes, checks, and
// splits at the midpoints for the linear scheme.
#include "remesh/oversample.h"

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>
#include <algorithm>
#include <string>
#include <unordered_map>

#include "remesh/adjacency.h"
#include "remesh/openmesh_types.h"
#include "wavelet/butterfly_subdivision.h"

namespace srcodec {
namespace {


Status check_indices(const TriangleMesh& mesh) {
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int32_t v : mesh.triangles[t])
      if (v < 0 || static_cast<size_t>(v) >= mesh.positions.size())
        return invalid_mesh("oversample: triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) +
                            ", outside the " + std::to_string(mesh.positions.size()) + " vertices");
  return ok_status();
}

StatusOr<OmMesh> to_openmesh(const TriangleMesh& mesh) {
  SRCODEC_RETURN_IF_ERROR(check_indices(mesh));
  OmMesh om;
  om.reserve(mesh.positions.size(), 3 * mesh.triangles.size() / 2, mesh.triangles.size());
  for (const Eigen::Vector3d& p : mesh.positions) om.add_vertex(OmMesh::Point(p.x(), p.y(), p.z()));
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const OmMesh::FaceHandle f = om.add_face(OmMesh::VertexHandle(tri[0]), OmMesh::VertexHandle(tri[1]),
                                             OmMesh::VertexHandle(tri[2]));
    if (!f.is_valid())
      return invalid_mesh("oversample: triangle " + std::to_string(t) +
                          " makes the mesh non-manifold or inconsistently oriented; split it into manifold "
                          "components first");
  }
  return om;
}

// One 1-to-4 split at the edges' midpoints: the surface does not change.
TriangleMesh split_at_midpoints(const TriangleMesh& mesh) {
  TriangleMesh out;
  out.positions = mesh.positions;
  out.triangles.reserve(4 * mesh.triangles.size());
  std::unordered_map<uint64_t, int32_t> midpoint;
  midpoint.reserve(3 * mesh.triangles.size() / 2);
  auto mid = [&](int32_t a, int32_t b) {
    const uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | static_cast<uint32_t>(std::max(a, b));
    const auto [it, added] = midpoint.emplace(key, static_cast<int32_t>(out.positions.size()));
    if (added) out.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]));
    return it->second;
  };
  for (const auto& t : mesh.triangles) {
    const int32_t m01 = mid(t[0], t[1]), m12 = mid(t[1], t[2]), m20 = mid(t[2], t[0]);
    out.triangles.push_back({t[0], m01, m20});
    out.triangles.push_back({t[1], m12, m01});
    out.triangles.push_back({t[2], m20, m12});
    out.triangles.push_back({m01, m12, m20});
  }
  return out;
}

}  // namespace

StatusOr<OversampleScheme> parse_oversample_scheme(const std::string& name, const std::string& flag) {
  if (name == "butterfly") return OversampleScheme::kButterfly;
  if (name == "loop") return OversampleScheme::kLoop;
  if (name == "linear") return OversampleScheme::kLinear;
  return invalid_argument(flag + " " + name + ": use butterfly, loop or linear");
}

StatusOr<TriangleMesh> oversample(const TriangleMesh& mesh, OversampleScheme scheme, int steps) {
  if (steps < 0 || steps > 3)
    return invalid_argument("oversample: " + std::to_string(steps) + " steps asked; use 0 to 3");
  if (steps == 0) return mesh;
  if (scheme == OversampleScheme::kLinear) {
    SRCODEC_RETURN_IF_ERROR(check_indices(mesh));
    TriangleMesh out = split_at_midpoints(mesh);
    for (int s = 1; s < steps; ++s) out = split_at_midpoints(out);
    return out;
  }
  SRCODEC_ASSIGN_OR_RETURN(OmMesh om, to_openmesh(mesh));
  bool done = false;
  if (scheme == OversampleScheme::kButterfly) {
    OpenMesh::Subdivider::Uniform::ModifiedButterflyT<OmMesh, double> butterfly;
    done = butterfly.attach(om) && butterfly(static_cast<size_t>(steps));
    butterfly.detach();
  } else {
    OpenMesh::Subdivider::Uniform::LoopT<OmMesh, double> loop;
    done = loop.attach(om) && loop(static_cast<size_t>(steps));
    loop.detach();
  }
  if (!done) return internal_error("oversample: OpenMesh's subdivider failed");
  TriangleMesh out;
  out.positions.reserve(om.n_vertices());
  for (const auto vh : om.vertices()) {
    const OmMesh::Point& p = om.point(vh);
    out.positions.emplace_back(p[0], p[1], p[2]);
  }
  out.triangles.reserve(om.n_faces());
  for (const auto fh : om.faces()) {
    std::array<int32_t, 3> tri{};
    int c = 0;
    for (const auto vh : om.fv_range(fh)) tri[c++] = vh.idx();
    out.triangles.push_back(tri);
  }
  return out;
}

StatusOr<TriangleMesh> oversample(const TriangleMesh& mesh, OversampleScheme scheme, int steps,
                                  std::vector<std::array<int32_t, 2>>* creases) {
  if (!creases || creases->empty() || steps == 0) return oversample(mesh, scheme, steps);
  if (steps < 0 || steps > 3)
    return invalid_argument("oversample: " + std::to_string(steps) + " steps asked; use 0 to 3");
  if (scheme == OversampleScheme::kButterfly) {
    // The crease rules keep the creases sharp and their sides flat where they
    // were; OpenMesh's Butterfly would round them off with ripples.
    SRCODEC_ASSIGN_OR_RETURN(ButterflySubdivision fine, butterfly_subdivide(mesh, steps, *creases));
    *creases = std::move(fine.crease_edges);
    return std::move(fine.mesh);
  }
  // One step at a time: every scheme keeps the old vertices' numbers and
  // puts one new vertex on each old edge, the only new vertex both its ends
  // are joined to, so each crease edge's halves are found by adjacency.
  TriangleMesh out = mesh;
  for (int s = 0; s < steps; ++s) {
    const int32_t old_count = static_cast<int32_t>(out.positions.size());
    SRCODEC_ASSIGN_OR_RETURN(out, oversample(out, scheme, 1));
    const Adjacency adj = vertex_neighbors(out.positions.size(), out.triangles);
    std::vector<std::array<int32_t, 2>> halves;
    halves.reserve(2 * creases->size());
    for (const auto& [a, b] : *creases) {
      int32_t middle = -1;
      for (const int32_t* m = adj.begin(a); m != adj.end(a); ++m)
        if (*m >= old_count && std::binary_search(adj.begin(b), adj.end(b), *m)) middle = *m;
      if (middle < 0)
        return invalid_argument("oversample: crease (" + std::to_string(a) + ", " + std::to_string(b) +
                                ") is not an edge of the mesh");
      halves.push_back({std::min(a, middle), std::max(a, middle)});
      halves.push_back({std::min(b, middle), std::max(b, middle)});
    }
    std::sort(halves.begin(), halves.end());
    *creases = std::move(halves);
  }
  return out;
}

}  // namespace srcodec
