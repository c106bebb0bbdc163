// Base-mesh site selection: a centroidal Voronoi tessellation of the input
// vertices grown by LBG splitting and Lloyd relaxation (Kammoun, Payan,
// Antonini, §II-B, §II-C and §III-A, Eqs. 1-3).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

struct LbgOptions {
  // Number of sites (= base mesh vertices) wanted, 1 ..= vertex count. A
  // closed component needs at least 4 for its base mesh to be a polyhedron
  // (a tetrahedron); that is the caller's choice, not checked here.
  size_t target_sites = 0;
  // Lloyd steps per LBG round, >= 0. A round stops earlier when the cells no
  // longer change, or when a step lowers the energy (Eq. 3) by less than
  // min_relative_decrease of it.
  int max_lloyd_iterations = 50;
  // Lloyd's tail is long and flat: stopping there costs little energy and
  // saves most of the steps. 0 runs every round to a fixed point or the step
  // budget.
  double min_relative_decrease = 1e-3;
  // Ours, not the paper's: once LBG has its target, a cell whose vector area
  // (the sum of its triangles' area-weighted normals) is less than this
  // fraction of its area is split across its normals (no Lloyd after), in up
  // to 4 rounds, adding at most target_sites / 4 sites. Such a cell wraps
  // around a thin part (a tube, a flap's rim), and its base triangles would
  // cut through it. On a cap of a sphere spanning 2θ the fraction is
  // (1 + cos θ) / 2; around a tube, half the circumference gives 2/π. 0: off.
  double min_flatness = 0.0;
  // No effect: nothing is random (splits follow the principal axis). Kept so
  // a randomized variant would not change the options' shape.
  uint64_t seed = 1;
};

struct VoronoiCells {
  std::vector<int32_t> sites;    // input vertex index of each site, all distinct
  std::vector<int32_t> cell_of;  // per input vertex: index into `sites` of its cell
};

// What the run did, for logs and tests.
struct LbgReport {
  struct Round {
    size_t sites = 0;  // after this round's splits
    // Eq. 3 with the cells' centroids (Eq. 2) as generators: [0] after the
    // split, then one per Lloyd step; a last entry not below the one before
    // is a step that was undone.
    std::vector<double> energy;
    double site_energy = 0.0;        // Eq. 3 of the round's result, with its sites as generators
    size_t reassigned_vertices = 0;  // vertices moved by the connectivity repair, summed over the round
    size_t curled_splits = 0;        // cells split for LbgOptions::min_flatness (0 in LBG's own rounds)
  };
  std::vector<Round> rounds;
};

// Picks options.target_sites input vertices as Voronoi sites (Eq. 1 with the
// Euclidean distance, density rho from vertex_density) and returns the
// tessellation:
//  - LBG: one site at the vertex nearest the density-weighted centroid, then
//    rounds that split every cell in two along its principal axis (only the
//    cells of largest energy, Eq. 3, when doubling would overshoot), each
//    followed by Lloyd relaxation. Lloyd steps use the cells' mass centroids
//    (Eq. 2) as generators; each cell's site is its vertex nearest its
//    centroid (§II-C), and a last assignment per round makes the cells the
//    sites' own Voronoi cells (Eq. 1 with the returned sites).
//  - Cells are connected on the surface: after each nearest-site assignment,
//    pieces of a cell not edge-connected to its site go to the neighbouring
//    cell they share most edges with. Every cell holds its site, so none is
//    empty.
//  - Deterministic: the result depends only on the input, not on threads.
//  - With options.min_flatness, cells that wrap around thin parts are split
//    afterwards, so there may be up to target_sites / 4 more sites.
// `mesh` must be one edge-connected component of triangles with every vertex
// used (split components first); anything else is an error, as is a target
// outside 1 ..= vertex count.
StatusOr<VoronoiCells> lbg_sites(const TriangleMesh& mesh, const LbgOptions& options,
                                 LbgReport* report = nullptr);

// Eq. 3 in discrete form: sum over vertices of rho(v) * |v - s(v)|^2, with
// s(v) the site of v's cell.
double voronoi_energy(const TriangleMesh& mesh, const std::vector<double>& density, const VoronoiCells& cells);

}  // namespace srcodec
