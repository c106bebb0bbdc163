#include "remesh/small_lp.h"

#include <limits>
#include <vector>

namespace srcodec {

bool maximize_lp(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& objective,
                 Eigen::VectorXd* x, int max_pivots) {
  const Eigen::Index m = A.rows(), n = A.cols();
  // Columns: the n variables, then one slack per row, then the right-hand
  // side. Row m holds the negated objective (the reduced costs).
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m + 1, n + m + 1);
  T.topLeftCorner(m, n) = A;
  T.block(0, n, m, m).setIdentity();
  T.col(n + m).head(m) = b;
  T.row(m).head(n) = -objective.transpose();
  std::vector<Eigen::Index> basis(static_cast<size_t>(m));
  for (Eigen::Index i = 0; i < m; ++i) basis[static_cast<size_t>(i)] = n + i;
  constexpr double kEps = 1e-12;
  for (int pivot = 0;; ++pivot) {
    Eigen::Index enter = -1;
    for (Eigen::Index j = 0; j < n + m && enter < 0; ++j)
      if (T(m, j) < -kEps) enter = j;
    if (enter < 0) break;  // optimal
    if (pivot == max_pivots) return false;
    Eigen::Index leave = -1;
    double best = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < m; ++i) {
      if (T(i, enter) <= kEps) continue;
      const double ratio = T(i, n + m) / T(i, enter);
      if (ratio < best - kEps ||
          (ratio <= best + kEps && leave >= 0 && basis[static_cast<size_t>(i)] < basis[static_cast<size_t>(leave)])) {
        best = ratio;
        leave = i;
      }
    }
    if (leave < 0) return false;  // unbounded
    T.row(leave) /= T(leave, enter);
    for (Eigen::Index i = 0; i <= m; ++i)
      if (i != leave && T(i, enter) != 0.0) T.row(i) -= T(i, enter) * T.row(leave);
    basis[static_cast<size_t>(leave)] = enter;
  }
  x->setZero(n);
  for (Eigen::Index i = 0; i < m; ++i)
    if (basis[static_cast<size_t>(i)] < n) (*x)(basis[static_cast<size_t>(i)]) = T(i, n + m);
  return true;
}

}  // namespace srcodec
