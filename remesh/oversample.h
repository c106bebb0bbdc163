// Oversampling of inputs that are coarse for the requested levels (Kammoun,
// Payan, Antonini §IV): the Voronoi cells are built on the input's vertices,
// and Euclidean cells only follow the surface when the sampling is dense
// compared with the semi-regular output, so a coarse input is first
// subdivided, with the interpolating Butterfly scheme (Dyn, Levin, Gregory
// 1990, in Zorin's modified form) or, for the paper's comparison in Fig. 6,
// the approximating Loop scheme. Linear (1-to-4 at the edges' midpoints) is
// ours: it adds vertices without moving the surface off the input's facets.
#pragma once


#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

enum class OversampleScheme { kButterfly, kLoop, kLinear };

// "butterfly", "loop" or "linear"; anything else is an invalid_argument that
// names `flag` (e.g. "--scheme") and the accepted names.
StatusOr<OversampleScheme> parse_oversample_scheme(const std::string& name, const std::string& flag);

// `steps` rounds (0..3) of 1-to-4 subdivision of one manifold, consistently
// oriented component (an element of split_into_manifold_components's result).
// Butterfly keeps every input vertex where it was (vertex i of the input is
// vertex i of the output); Loop moves them; Linear keeps them and puts the
// new ones on the input's triangles, so the surface stays the input's.
// Butterfly and Loop use their boundary rules (4-point / cubic B-spline);
// either way boundary loops stay loops. Errors: steps outside 0..3, indices
// outside the vertices, or (Butterfly, Loop) a mesh OpenMesh cannot take as
// a manifold.
StatusOr<TriangleMesh> oversample(const TriangleMesh& mesh, OversampleScheme scheme, int steps);

// The same, carrying `creases` (edges (a, b) of `mesh`, a < b, sorted)
// through: on return each is replaced by the 2^steps edges that subdivide
// it, sorted. Butterfly then uses the crease rules of the codec's own
// stencils (wavelet/butterfly_subdivision.h), which keep creases sharp.
StatusOr<TriangleMesh> oversample(const TriangleMesh& mesh, OversampleScheme scheme, int steps,
                                  std::vector<std::array<int32_t, 2>>* creases);

}  // namespace srcodec
