// The last level's splits undone where its triangles stay tangled (ours, not
// in the paper): after the untangling (remesh/untangle.h), a triangle of the
// finest level still folded or in a pleat is taken out with its siblings by
// leaving its parent, and the parent's neighbours around one corner,
// unsplit. The remesher then untangles again (RemeshOptions::unsplit_tangles,
// off by default: it costs bytes in every prefix of a coded file).
//
// Why: where the input is crumpled at the scale of a finest triangle (a
// mouth, claws, thin pieces) no place of the finest level's
// vertices, moved one at a time or together, faces every triangle out; the
// level above, with fewer vertices to place, usually can be. The paper
// refines only where a triangle's cells hold enough input vertices; this
// also leaves a triangle whole where its children cannot face the way the
// input does. The coarser levels keep their triangles.
//
// Why around a corner: the closure splits a triangle left with two or three
// split neighbours (TriangleHierarchy::split), so a lone parent would be
// split again. Every triangle of a vertex's star has one edge on the star's
// rim, the only one a split neighbour can hang a vertex on (green).
//
// Why not everywhere: where a star's children reach far out of it (a thin
// spike or flap the finest level follows and the level above would cut
// off), leaving it whole costs more PSNR than the folds are worth.
#pragma once

#include <cstddef>

#include "format/mesh.h"
#include "format/status.h"
#include "remesh/folds.h"
#include "format/semi_regular/semi_regular_mesh.h"

namespace srcodec {

struct UnsplitOptions {
  // A star is left whole only where no new vertex of its children lies
  // further than this many times its edge from the edge's midpoint.
  double max_reach = 2.0;
  // Also at the corners of the coarser levels' tangled triangles: the star
  // among them chosen as for the finest level's. The coarser levels keep
  // their triangles, but a corner with no finest triangles around it is
  // free to move as its own levels ask.
  bool coarser = false;
};

struct UnsplitReport {
  size_t stars = 0;   // vertex stars of level L - 1 unsplit
  size_t undone = 0;  // splits undone (the closure may split a star's triangle again)
  FoldCount before;   // the finest level's tangled triangles in `mesh` (the result is judged by the untangling)
  double seconds = 0.0;
};

// `mesh` with splits of level L - 1 (L = mesh.levels) undone. For each
// triangle of the finest level folded or in a pleat (judged by the normals
// of the vertices of `sides`, the oversampled input the remesher ran on,
// nearest its corners, as the fit and the untangling judge) that is a child
// of a split of level L - 1 whose children are leaves, or is a leaf of level
// L - 1 itself (left whole before, or bisected by the closure): the splits
// of the level L - 1 triangles around the corner of that parent (or leaf)
// whose star holds most tangled children, the lowest vertex id on a tie,
// among the corners whose star has a split left and reaches out by at most
// options.max_reach; with options.coarser, then likewise for the tangled
// triangles of every coarser level but the base, among their own corners.
// Vertices keep their positions; those only the undone children had are
// dropped. Deterministic. Returns `mesh` when no star is chosen.
StatusOr<SemiRegularMesh> unsplit_tangles(const TriangleMesh& sides, const SemiRegularMesh& mesh,
                                          const UnsplitOptions& options = {}, UnsplitReport* report = nullptr);
// The same with the sides of `sides`'s vertices already built (the remesher
// keeps one across its passes).
StatusOr<SemiRegularMesh> unsplit_tangles(const FoldCounter::Sides& sides, const SemiRegularMesh& mesh,
                                          const UnsplitOptions& options = {}, UnsplitReport* report = nullptr);

}  // namespace srcodec
