// Bjøntegaard delta rate, ITU-T VCEG-M33 (2001): cubic least-squares fit of
// log10(rate) against PSNR per curve, integrated over the shared PSNR range.
#include "tools/measure/bd_rate.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <string>

namespace srcodec {
namespace {

// A polynomial in u = (psnr - center) / scale: centring and scaling keep the
// least-squares system well conditioned for PSNRs around 30..100 dB.
struct LogRateFit {
  Eigen::VectorXd coefficients;  // lowest degree first
  double center = 0, scale = 1;

  // The integral of the fit over [a, b] (in PSNR).
  double integral(double a, double b) const {
    const double ua = (a - center) / scale, ub = (b - center) / scale;
    double sum = 0;
    for (Eigen::Index k = 0; k < coefficients.size(); ++k) {
      const double power = static_cast<double>(k + 1);
      sum += coefficients[k] * (std::pow(ub, power) - std::pow(ua, power)) / power;
    }
    return sum * scale;
  }
};

LogRateFit fit_log_rate(const RdCurve& front) {
  const auto n = static_cast<Eigen::Index>(front.size());
  const Eigen::Index terms = std::min<Eigen::Index>(4, n);
  LogRateFit fit;
  const double low = front.front().psnr, high = front.back().psnr;
  fit.center = 0.5 * (low + high);
  fit.scale = std::max(0.5 * (high - low), 1e-9);
  Eigen::MatrixXd vandermonde(n, terms);
  Eigen::VectorXd log_rate(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u = (front[i].psnr - fit.center) / fit.scale;
    double power = 1;
    for (Eigen::Index k = 0; k < terms; ++k, power *= u) vandermonde(i, k) = power;
    log_rate[i] = std::log10(front[i].rate);
  }
  fit.coefficients = vandermonde.colPivHouseholderQr().solve(log_rate);
  return fit;
}

// log10(rate) on the front at `psnr`, which must lie in its PSNR range.
double log_rate_on_front(const RdCurve& front, double psnr) {
  auto upper = std::upper_bound(front.begin(), front.end(), psnr,
                                [](double p, const RdPoint& q) { return p < q.psnr; });
  if (upper == front.end()) return std::log10(front.back().rate);
  if (upper == front.begin()) return std::log10(front.front().rate);
  const RdPoint& a = *(upper - 1);
  const RdPoint& b = *upper;
  const double t = (psnr - a.psnr) / (b.psnr - a.psnr);
  return (1 - t) * std::log10(a.rate) + t * std::log10(b.rate);
}

struct Overlap {
  double low = 0, high = 0;
  bool empty() const { return !(high > low); }
};

Overlap shared_range(const RdCurve& a, const RdCurve& b) {
  if (a.empty() || b.empty()) return {};
  return {std::max(a.front().psnr, b.front().psnr), std::min(a.back().psnr, b.back().psnr)};
}

// (psnr, log10 rate_a - log10 rate_b) at every measured PSNR of either front
// inside the overlap and at its ends: both curves are linear between these.
std::vector<std::pair<double, double>> log_rate_differences(const RdCurve& a, const RdCurve& b,
                                                            const Overlap& range) {
  std::vector<double> psnrs = {range.low, range.high};
  for (const RdCurve* c : {&a, &b})
    for (const RdPoint& p : *c)
      if (p.psnr > range.low && p.psnr < range.high) psnrs.push_back(p.psnr);
  std::sort(psnrs.begin(), psnrs.end());
  psnrs.erase(std::unique(psnrs.begin(), psnrs.end()), psnrs.end());
  std::vector<std::pair<double, double>> out;
  out.reserve(psnrs.size());
  for (double p : psnrs) out.emplace_back(p, log_rate_on_front(a, p) - log_rate_on_front(b, p));
  return out;
}

}  // namespace

RdCurve rd_front(const RdCurve& curve) {
  RdCurve valid;
  for (const RdPoint& p : curve)
    if (std::isfinite(p.rate) && p.rate > 0 && std::isfinite(p.psnr)) valid.push_back(p);
  std::sort(valid.begin(), valid.end(), [](const RdPoint& a, const RdPoint& b) {
    return a.rate != b.rate ? a.rate < b.rate : a.psnr > b.psnr;
  });
  RdCurve front;
  for (const RdPoint& p : valid)
    if (front.empty() || p.psnr > front.back().psnr) front.push_back(p);
  return front;
}

StatusOr<BdRate> bd_rate(const RdCurve& anchor, const RdCurve& test) {
  const RdCurve a = rd_front(anchor), t = rd_front(test);
  if (a.size() < 2 || t.size() < 2)
    return invalid_argument("BD-rate needs at least 2 useful points per curve (anchor has " +
                            std::to_string(a.size()) + ", test " + std::to_string(t.size()) + ")");
  const Overlap range = shared_range(a, t);
  if (range.empty())
    return invalid_argument("BD-rate: the PSNR ranges do not overlap (anchor " + std::to_string(a.front().psnr) +
                            ".." + std::to_string(a.back().psnr) + " dB, test " + std::to_string(t.front().psnr) +
                            ".." + std::to_string(t.back().psnr) + " dB)");
  const double width = range.high - range.low;
  BdRate r;
  r.psnr_low = range.low;
  r.psnr_high = range.high;
  const double mean_fit =
      (fit_log_rate(t).integral(range.low, range.high) - fit_log_rate(a).integral(range.low, range.high)) / width;
  r.delta = std::pow(10.0, mean_fit) - 1.0;
  // Trapezoids are exact here: the difference is linear between breakpoints.
  const auto d = log_rate_differences(t, a, range);
  double area = 0;
  for (size_t i = 1; i < d.size(); ++i) area += 0.5 * (d[i].second + d[i - 1].second) * (d[i].first - d[i - 1].first);
  r.linear_delta = std::pow(10.0, area / width) - 1.0;
  return r;
}

std::optional<double> rate_at_psnr(const RdCurve& curve, double psnr) {
  const RdCurve front = rd_front(curve);
  if (front.empty() || !(psnr >= front.front().psnr && psnr <= front.back().psnr)) return std::nullopt;
  return std::pow(10.0, log_rate_on_front(front, psnr));
}

std::vector<double> crossover_psnrs(const RdCurve& a, const RdCurve& b) {
  const RdCurve fa = rd_front(a), fb = rd_front(b);
  const Overlap range = shared_range(fa, fb);
  std::vector<double> out;
  if (range.empty()) return out;
  const auto d = log_rate_differences(fa, fb, range);
  // A crossing is a change of sign; where the curves run together (zeros)
  // before the sign changes, the first point of that stretch is reported.
  int last_sign = 0;
  size_t last_nonzero = 0;
  for (size_t i = 0; i < d.size(); ++i) {
    const int sign = (d[i].second > 0) - (d[i].second < 0);
    if (sign == 0) continue;
    if (last_sign != 0 && sign != last_sign) {
      if (last_nonzero + 1 == i) {
        const auto& [p0, d0] = d[i - 1];
        const auto& [p1, d1] = d[i];
        out.push_back(p0 + (p1 - p0) * d0 / (d0 - d1));
      } else {
        out.push_back(d[last_nonzero + 1].first);
      }
    }
    last_sign = sign;
    last_nonzero = i;
  }
  return out;
}

}  // namespace srcodec
