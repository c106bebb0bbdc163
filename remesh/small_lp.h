// A dense simplex for the untangling's small linear programs (ours): a
// vertex's fold-free region is an intersection of half-spaces, one per
// triangle around it (remesh/untangle.cpp), a few dozen rows in 3D.
#pragma once

#include <Eigen/Core>

namespace srcodec {

// Maximizes objective . x over x >= 0 with A x <= b, where every b is >= 0
// (so x = 0 is feasible): the simplex method on a dense tableau, with
// Bland's rule against cycling. Returns false, leaving *x alone, when the
// objective is unbounded or the method has not ended within max_pivots.
bool maximize_lp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& objective,
                 Eigen::VectorXd* x, int max_pivots = 500);

}  // namespace srcodec
