// Per-vertex density for the centroidal Voronoi tessellation of the input
// (Kammoun, Payan, Antonini, §II-C and Fig. 2: rho(v_i) = area of the dual
// cell of v_i, the weight in Eqs. 2 and 3).
#pragma once

#include <vector>

#include "format/mesh.h"

namespace srcodec {

// rho(v_i) = a third of the summed areas of the triangles incident to v_i (the
// barycentric dual cell), so the densities sum to the surface area. Vertices
// no triangle uses get 0. Triangle indices must be valid (lbg_sites checks
// them before calling this).
std::vector<double> vertex_density(const TriangleMesh& mesh);

}  // namespace srcodec
