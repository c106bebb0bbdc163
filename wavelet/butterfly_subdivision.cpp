// Subdivision as the decoder's inverse transform with zero details: refine a
// hierarchy over the mesh uniformly, build its LiftingPlan, and predict every
// level from the one below (no detail: no update to undo, no frame).
#include "wavelet/butterfly_subdivision.h"

#include <Eigen/Core>
#include <string>

#include "format/semi_regular/creases.h"
#include "format/semi_regular/hierarchy.h"
#include "wavelet/lifting.h"

namespace srcodec {

StatusOr<ButterflySubdivision> butterfly_subdivide(const TriangleMesh& mesh, int32_t steps,
                                                   const std::vector<std::array<int32_t, 2>>& crease_edges) {
  if (steps < 0) return invalid_argument("butterfly_subdivide: steps must be >= 0, got " + std::to_string(steps));
  const int32_t n = static_cast<int32_t>(mesh.positions.size());
  SRCODEC_ASSIGN_OR_RETURN(TriangleHierarchy hierarchy, TriangleHierarchy::create(n, mesh.triangles));
  for (int32_t level = 0; level < steps; ++level) {
    // The nodes of `level` are all leaves and all split: nothing unbalanced,
    // no green closure (split() leaves an already split node alone).
    const size_t count = hierarchy.nodes().size();
    for (size_t i = 0; i < count; ++i)
      if (hierarchy.nodes()[i].level == level) hierarchy.split(static_cast<int32_t>(i));
  }
  SRCODEC_ASSIGN_OR_RETURN(const LiftingPlan plan, LiftingPlan::build(hierarchy, steps, crease_edges));
  ButterflySubdivision out;
  out.crease_edges = crease_edges_up_to(hierarchy, crease_edges, steps);  // checked by the plan's build
  const std::vector<Eigen::Vector3d> zero(static_cast<size_t>(hierarchy.vertex_count()), Eigen::Vector3d::Zero());
  out.mesh.positions = inverse_lifting(plan, mesh.positions, zero, steps);
  out.mesh.triangles = hierarchy.level_triangles(steps);
  return out;
}

}  // namespace srcodec
