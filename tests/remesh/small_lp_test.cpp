#include "remesh/small_lp.h"

#include <gtest/gtest.h>

#include <cmath>

namespace srcodec {
namespace {

// max 3x + 5y with x <= 4, 2y <= 12, 3x + 2y <= 18: 36 at (2, 6).
TEST(SmallLp, FindsTheOptimalVertex) {
  Eigen::MatrixXd A(3, 2);
  A << 1, 0, 0, 2, 3, 2;
  const Eigen::VectorXd b = Eigen::Vector3d(4, 12, 18);
  Eigen::VectorXd x;
  ASSERT_TRUE(maximize_lp(A, b, Eigen::Vector2d(3, 5), &x));
  EXPECT_NEAR(x(0), 2.0, 1e-12);
  EXPECT_NEAR(x(1), 6.0, 1e-12);
}

// max x with -x + y <= 1: no bound.
TEST(SmallLp, SaysWhenUnbounded) {
  Eigen::MatrixXd A(1, 2);
  A << -1, 1;
  Eigen::VectorXd x = Eigen::Vector2d(7, 7);
  EXPECT_FALSE(maximize_lp(A, Eigen::VectorXd::Ones(1), Eigen::Vector2d(1, 0), &x));
  EXPECT_EQ(x, Eigen::Vector2d(7, 7));  // left alone
}

// Beale's degenerate problem, on which the largest-coefficient rule cycles
// for ever; Bland's rule ends at the optimum, 1.25 at (1, 0, 1, 0).
TEST(SmallLp, EndsOnBealesCyclingExample) {
  Eigen::MatrixXd A(3, 4);
  A << 0.25, -8, -1, 9, 0.5, -12, -0.5, 3, 0, 0, 1, 0;
  const Eigen::VectorXd b = Eigen::Vector3d(0, 0, 1);
  Eigen::VectorXd c(4);
  c << 0.75, -20, 0.5, -6;
  Eigen::VectorXd x;
  ASSERT_TRUE(maximize_lp(A, b, c, &x));
  EXPECT_NEAR(c.dot(x), 1.25, 1e-12);
  EXPECT_TRUE(((A * x).array() <= b.array() + 1e-12).all());
  EXPECT_TRUE((x.array() >= 0.0).all());
}

// The largest disc in the triangle x >= 0, y >= 0, x + y <= 2 (variables
// x, y, r): x - r >= 0, y - r >= 0 and x + y + sqrt(2) r <= 2 give the
// incircle, radius 2 / (2 + sqrt(2)).
TEST(SmallLp, FindsTheLargestDiscInATriangle) {
  Eigen::MatrixXd A(3, 3);
  A << -1, 0, 1, 0, -1, 1, 1, 1, std::sqrt(2.0);
  const Eigen::VectorXd b = Eigen::Vector3d(0, 0, 2);
  Eigen::VectorXd x;
  ASSERT_TRUE(maximize_lp(A, b, Eigen::Vector3d(0, 0, 1), &x));
  const double r = 2.0 / (2.0 + std::sqrt(2.0));
  EXPECT_NEAR(x(2), r, 1e-12);
  EXPECT_NEAR(x(0), r, 1e-12);
  EXPECT_NEAR(x(1), r, 1e-12);
}

}  // namespace
}  // namespace srcodec
