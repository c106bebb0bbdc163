// Bjøntegaard delta rate (G. Bjøntegaard, "Calculation of average PSNR
// differences between RD-curves", ITU-T VCEG-M33, 2001): log10(rate) is
// fitted as a cubic polynomial of PSNR per curve, both fits are integrated
// over the PSNR interval the two curves share, and the mean difference d of
// log-rates gives BD = 10^d - 1 (the test's average rate change at equal
// quality; -0.25: a quarter fewer bits). Plus the piecewise-linear readings
// of the same curves: rate at a given PSNR, crossovers, and the BD-rate with
// the fit replaced by linear interpolation of log-rate, as a cross-check.
#pragma once

#include <optional>
#include <vector>

#include "format/status.h"

namespace srcodec {

struct RdPoint {
  double rate = 0;  // > 0, any unit (bytes, bpv) as long as both curves use the same
  double psnr = 0;  // dB, finite
};
using RdCurve = std::vector<RdPoint>;

// The points worth choosing: sorted by rate, each with a higher PSNR than
// every cheaper one (points no better than a cheaper one are dropped, and of
// equal rates the best PSNR is kept). Non-finite or non-positive rates and
// non-finite PSNRs are dropped too. Every function below reads this front.
RdCurve rd_front(const RdCurve& curve);

struct BdRate {
  double delta = 0;         // 10^mean(log10 test - log10 anchor) - 1
  double linear_delta = 0;  // the same with piecewise-linear log-rate instead of the cubic fit
  double psnr_low = 0, psnr_high = 0;  // the shared PSNR interval integrated over
};

// Test against anchor. Each front needs at least 2 points (the fit's degree
// is min(3, points - 1)); the fronts' PSNR ranges must overlap on an interval
// of positive length. Errors (kInvalidArgument) say which condition failed.
StatusOr<BdRate> bd_rate(const RdCurve& anchor, const RdCurve& test);

// The rate at `psnr` on the curve's front, linear in log10(rate) between the
// two measured points around it; nullopt outside the measured PSNR range.
std::optional<double> rate_at_psnr(const RdCurve& curve, double psnr);

// The PSNRs where the fronts' piecewise-linear log-rate curves cross (the
// sign of log rate_a - log rate_b changes), ascending, within the shared
// PSNR range; empty when one is cheaper throughout or they do not overlap.
std::vector<double> crossover_psnrs(const RdCurve& a, const RdCurve& b);

}  // namespace srcodec
