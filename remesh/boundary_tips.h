// Sites at the tips of the input's narrow holes (ours, not in the paper).
//
// Scans can have slits: holes narrower than a base edge. LBG's cells do not see them, so the base mesh's boundary can run
// from one side of a slit to the other with no vertex at its tip; the
// finer levels then either cut across the tip (triangles over the hole,
// far off the input, which can hold most of a remesh's squared error) or
// fan around it in long sheared triangles that fold. A site at each
// tip makes the base boundary turn there.
#pragma once

#include <cstddef>

#include "format/mesh.h"
#include "remesh/lbg_sites.h"

namespace srcodec {

struct BoundaryTipOptions {
  double reach = 0.0;               // how far along the loop a turn is measured, either way (mesh units)
  double min_turn_degrees = 100.0;  // a tip turns by more than this over 2 x reach
};

// Adds to `cells` (sites and cells over `mesh`) a site at each tip of the
// boundary loops of `mesh`: a boundary vertex where the loop, followed
// `reach` along its length either way, turns by more than
// `min_turn_degrees` (the angle between the chords from the point behind
// it to it and from it to the point ahead), and turns most within `reach`
// either way. A tip that is already a site is left. The new site's cell is
// its old cell's part reached from it over the mesh's edges through
// vertices nearer to it than to the old site. Loops that are not simple
// cycles are skipped. Returns the sites added; deterministic.
size_t add_boundary_tip_sites(const TriangleMesh& mesh, const BoundaryTipOptions& options, VoronoiCells* cells);

// The reach the remesher uses: half the edge of an equilateral triangle
// mesh of 2 x `sites` triangles over the mesh's area.
double boundary_tip_reach(const TriangleMesh& mesh, size_t sites);

}  // namespace srcodec
