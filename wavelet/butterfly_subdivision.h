// Modified Butterfly subdivision of a plain triangle mesh with the wavelet's
// own prediction stencils (LiftingPlan, wavelet/README.md), creases included:
// one definition of the Butterfly for the codec and for anything else that
// subdivides (the remesher's oversampling of coarse inputs, remesh/oversample.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

struct ButterflySubdivision {
  // Vertex i of the input is vertex i here, at the same position (the scheme
  // interpolates); the new vertices follow, coarser levels first.
  TriangleMesh mesh;
  // The edges of `mesh` that refine the input's creases (a < b, sorted): the
  // creases to give a further subdivision or LiftingPlan::build.
  std::vector<std::array<int32_t, 2>> crease_edges;
};

// `steps` (>= 0) rounds of 1-to-4 subdivision, each new vertex placed by the
// stencil LiftingPlan predicts it with (the modified Butterfly of Zorin,
// Schröder, Sweldens 1996; along and beside `crease_edges` the crease rules
// of wavelet/README.md, "Creases"). Without creases the positions are those
// of OpenMesh's Subdivider::Uniform::ModifiedButterflyT, to rounding.
// `mesh`: manifold and consistently oriented, every vertex used, as
// TriangleHierarchy::create requires; `crease_edges`: edges of `mesh` as
// LiftingPlan::build takes them (a < b, sorted, no repeats). Errors: theirs,
// or steps < 0.
StatusOr<ButterflySubdivision> butterfly_subdivide(const TriangleMesh& mesh, int32_t steps,
                                                   const std::vector<std::array<int32_t, 2>>& crease_edges = {});

}  // namespace srcodec
