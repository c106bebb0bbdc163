#include "tools/measure/bd_rate.h"

#include <gtest/gtest.h>

#include <cmath>

namespace srcodec {
namespace {

// A Draco-like curve: about 6 dB per doubling of the rate, slightly bent.
RdCurve reference_curve() {
  return {{1000, 38.2}, {1500, 43.0}, {2300, 48.9}, {3400, 54.1}, {5200, 60.3}, {7900, 66.0}, {12000, 71.8}};
}

RdCurve scaled(const RdCurve& c, double factor) {
  RdCurve out = c;
  for (RdPoint& p : out) p.rate *= factor;
  return out;
}

TEST(BdRate, IdenticalCurvesGiveZero) {
  auto r = bd_rate(reference_curve(), reference_curve());
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(r->delta, 0.0, 1e-12);
  EXPECT_NEAR(r->linear_delta, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(r->psnr_low, 38.2);
  EXPECT_DOUBLE_EQ(r->psnr_high, 71.8);
}

TEST(BdRate, HalfTheRateGivesMinusFiftyPercent) {
  auto r = bd_rate(reference_curve(), scaled(reference_curve(), 0.5));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_NEAR(r->delta, -0.5, 1e-9);
  EXPECT_NEAR(r->linear_delta, -0.5, 1e-9);
  // And the other way round: twice the rate, +100%.
  auto back = bd_rate(scaled(reference_curve(), 0.5), reference_curve());
  ASSERT_TRUE(back.ok());
  EXPECT_NEAR(back->delta, 1.0, 1e-9);
}

// Straight lines in log-rate: log10 r = 2 + (p - 40) / 20 (anchor) and
// 1.5 + (p - 40) / 10 (test). Over the shared range 40..60 dB the
// difference is -0.5 + (p - 40) / 20, whose mean is 0: BD-rate 0, although
// the test is cheaper below 50 dB and dearer above (crossover at 50 dB).
// The cubic fit reproduces lines exactly, so both figures agree.
TEST(BdRate, HandComputedLinesAndCrossover) {
  RdCurve anchor, test;
  for (double p : {30.0, 40.0, 50.0, 60.0, 70.0}) anchor.push_back({std::pow(10.0, 2 + (p - 40) / 20), p});
  for (double p : {40.0, 45.0, 50.0, 55.0, 60.0}) test.push_back({std::pow(10.0, 1.5 + (p - 40) / 10), p});
  auto r = bd_rate(anchor, test);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_DOUBLE_EQ(r->psnr_low, 40.0);
  EXPECT_DOUBLE_EQ(r->psnr_high, 60.0);
  EXPECT_NEAR(r->delta, 0.0, 1e-9);
  EXPECT_NEAR(r->linear_delta, 0.0, 1e-9);
  const std::vector<double> x = crossover_psnrs(test, anchor);
  ASSERT_EQ(x.size(), 1u);
  EXPECT_NEAR(x[0], 50.0, 1e-9);
  // Shifting the test up by 0.1 in log10 over the range: 10^0.1 - 1 = +25.9%.
  auto shifted = bd_rate(anchor, scaled(test, std::pow(10.0, 0.1)));
  ASSERT_TRUE(shifted.ok());
  EXPECT_NEAR(shifted->delta, std::pow(10.0, 0.1) - 1, 1e-9);
}

// Four points determine the cubic: the fit is exact, and its integral is the
// hand-computed one. log10 r = 3 + u^3 / 8 with u = p - 50, sampled at
// 46, 48, 52, 54 dB, against a flat log10 r = 3: over 46..54 dB (u in -4..4)
// the mean of u^3 / 8 is 0; over 48..54 dB it is [u^4 / 32] from -2 to 4,
// divided by 6: (256 - 16) / 32 / 6 = 1.25, so BD = 10^1.25 - 1.
TEST(BdRate, CubicFitIsExactOnFourPoints) {
  RdCurve cubic, flat;
  for (double p : {46.0, 48.0, 52.0, 54.0}) cubic.push_back({std::pow(10.0, 3 + std::pow(p - 50, 3) / 8), p});
  for (double p : {46.0, 50.0, 54.0}) flat.push_back({1000.0 + (p - 46) * 1e-9, p});
  auto symmetric = bd_rate(flat, cubic);
  ASSERT_TRUE(symmetric.ok()) << symmetric.status().message();
  EXPECT_NEAR(symmetric->delta, 0.0, 1e-6);
  RdCurve upper = flat;
  upper.front() = {1000.0, 48.0};
  auto r = bd_rate(upper, cubic);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->delta, std::pow(10.0, 1.25) - 1, 1e-6);
}

TEST(BdRate, RateAtPsnrInterpolatesLogRateInsideTheRangeOnly) {
  const RdCurve c = {{100, 40}, {400, 50}, {1600, 60}};
  ASSERT_TRUE(rate_at_psnr(c, 45).has_value());
  EXPECT_NEAR(*rate_at_psnr(c, 45), 200.0, 1e-9);  // geometric mean, not 250
  EXPECT_NEAR(*rate_at_psnr(c, 40), 100.0, 1e-9);
  EXPECT_NEAR(*rate_at_psnr(c, 60), 1600.0, 1e-9);
  EXPECT_NEAR(*rate_at_psnr(c, 57.5), 400.0 * std::pow(4.0, 0.75), 1e-9);
  EXPECT_FALSE(rate_at_psnr(c, 39.9).has_value());
  EXPECT_FALSE(rate_at_psnr(c, 60.1).has_value());
  EXPECT_FALSE(rate_at_psnr({}, 50).has_value());
}

TEST(BdRate, FrontDropsDominatedAndInvalidPoints) {
  const RdCurve c = {{400, 50}, {100, 40}, {800, 49}, {400, 48}, {0, 45}, {200, NAN}, {1600, 60}, {1700, 60}};
  const RdCurve f = rd_front(c);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0].rate, 100);
  EXPECT_EQ(f[1].rate, 400);
  EXPECT_EQ(f[1].psnr, 50);
  EXPECT_EQ(f[2].rate, 1600);
  // A saturating curve (more bytes, no better) reads like its front.
  RdCurve saturating = reference_curve();
  saturating.push_back({50000, 71.8});
  auto r = bd_rate(reference_curve(), saturating);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->delta, 0.0, 1e-12);
}

TEST(BdRate, NoCrossoverWhenOneIsCheaperThroughout) {
  EXPECT_TRUE(crossover_psnrs(reference_curve(), scaled(reference_curve(), 0.7)).empty());
  const RdCurve low = {{100, 30}, {200, 35}}, high = {{100, 40}, {200, 45}};
  EXPECT_TRUE(crossover_psnrs(low, high).empty());  // no shared range
}

TEST(BdRate, ErrorsSayWhatIsMissing) {
  auto few = bd_rate(reference_curve(), {{100, 50}});
  ASSERT_FALSE(few.ok());
  EXPECT_NE(few.status().message().find("at least 2"), std::string::npos) << few.status().message();
  auto apart = bd_rate({{100, 30}, {200, 35}}, {{100, 40}, {200, 45}});
  ASSERT_FALSE(apart.ok());
  EXPECT_NE(apart.status().message().find("do not overlap"), std::string::npos) << apart.status().message();
}

}  // namespace
}  // namespace srcodec
