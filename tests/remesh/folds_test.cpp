#include "remesh/folds.h"

#include <gtest/gtest.h>

#include <cmath>

namespace srcodec {
namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();

TEST(Folds, ATriangleIsFoldedWhenItFacesAgainstItsCornersSides) {
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Eigen::Vector3d> up(3, kUp), down(3, -kUp);
  EXPECT_FALSE(folded(p, up, {0, 1, 2}));
  EXPECT_TRUE(folded(p, down, {0, 1, 2}));
  EXPECT_TRUE(folded(p, up, {0, 2, 1}));
  EXPECT_TRUE(folded(p, up, {0, 1, 1}));  // no area: folded
  EXPECT_EQ(fold_depth(facing(p, up, {0, 1, 2})), 0.0);
  EXPECT_GT(fold_depth(facing(p, up, {0, 2, 1})), 0.0);
}

TEST(Folds, NeighboursMeetingPast150DegreesArePleats) {
  auto normal_at = [](double degrees) {  // the normal of a neighbour turned by this much about the shared edge
    const double a = degrees * M_PI / 180.0;
    return Eigen::Vector3d(std::sin(a), 0.0, std::cos(a));
  };
  EXPECT_FALSE(pleat(kUp, normal_at(140.0)));
  EXPECT_TRUE(pleat(kUp, normal_at(160.0)));
  EXPECT_EQ(pleat_depth(kUp, normal_at(140.0)), 0.0);
  EXPECT_GT(pleat_depth(kUp, normal_at(170.0)), pleat_depth(kUp, normal_at(160.0)));
}

TEST(Folds, CountBySidesCountsAndMarksBoth) {
  // Two triangles over the edge 0-1, the second folded right over the first.
  const std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, 1, 0.01}};
  const std::vector<std::array<int32_t, 3>> tris = {{0, 1, 2}, {1, 0, 3}};
  std::vector<char> marked;
  const FoldCount c = count_by_sides(p, std::vector<Eigen::Vector3d>(4, kUp), tris, &marked);
  EXPECT_EQ(c.folded_by_nearest_input, 1u);
  EXPECT_EQ(c.pleats, 1u);
  EXPECT_EQ(marked, (std::vector<char>{1, 1}));
}

}  // namespace
}  // namespace srcodec
