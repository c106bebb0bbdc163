// `srcodec rd MESH -o DIR`: the rate-distortion comparison of DESIGN.md
// "Measuring". srcodec: one remesh and one full embedded stream, cut at
// log-spaced sizes from the base mesh alone to the whole stream; Draco: -cl 10
// at 6..16 quantization bits. Every decoded mesh is measured against the
// input with the same surface_distance options and, unless --no-visual, the
// same visual measure (tools/measure/visual_difference.h); rd.csv, rd.png (by
// tools/rd_plot.py) and a summary: Bjøntegaard delta rate (VCEG-M33), byte
// ratios at 50/60/70 dB, the visual figures there at equal bytes, crossovers
// and time ratios.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "codec/srm_codec.h"
#include "format/file_io.h"
#include "format/mesh_files/mesh_io.h"
#include "tools/measure/bd_rate.h"
#include "tools/measure/draco_baseline.h"
#include "tools/measure/surface_distance.h"
#include "tools/measure/visual_difference.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"
#include "tools/srcodec/remesh_flags.h"
#include "tools/srcodec/remesh_progress.h"
#include "tools/srcodec/visual_flags.h"

#ifndef SRCODEC_SOURCE_DIR
#define SRCODEC_SOURCE_DIR "."
#endif

namespace srcodec {
namespace {

constexpr int kDracoMinBits = 6, kDracoMaxBits = 16, kDracoLevel = 10;
constexpr double kRatioPsnrs[] = {50.0, 60.0, 70.0};
// A BD-rate over a shared PSNR range narrower than this is printed with a
// caution: it averages over too little of either curve to say much.
constexpr double kNarrowOverlapDb = 3.0;
// When the cubic fit and the piecewise-linear reading differ by more than
// this (as fractions of rate), a curve bends more than a cubic follows.
constexpr double kFitDisagreement = 0.05;

struct RdCliOptions {
  std::string input, out_dir;
  RemeshFlags remesh;
  int points = 10;
  size_t samples = 200000;
  // truncate: the files `srcodec encode --bytes N` writes (truncate_srm, a
  // table listing only the segments kept); prefix: the first N bytes of the
  // whole stream, as a streaming decoder would receive them.
  std::string cut = "truncate";
  VisualOptions visual;
  bool json = false, quiet = false, no_plot = false, no_visual = false;
};

struct RdRow {
  std::string codec, setting;
  uint64_t bytes = 0;
  double bpv = 0, psnr = 0, rms = 0, hausdorff = 0, encode_ms = 0, decode_ms = 0;
  // tools/measure/visual_difference.h; NaN with --no-visual.
  double normal_degrees = NAN, defect_share = NAN, depth_psnr = NAN, turned_over_share = NAN;
};

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::string fixed(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, value);
  return buffer;
}

class RdRun {
 public:
  RdRun(const RdCliOptions& o, TriangleMesh input) : o_(o), input_(std::move(input)) {
    metric_.samples_per_surface = o.samples;
  }
  // The input's half of the metric (its samples and search) and its
  // renders, made once for every decoded mesh to be compared with.
  Status init() {
    SRCODEC_ASSIGN_OR_RETURN(SurfaceReference s, SurfaceReference::build(input_, metric_, cgal_search));
    surface_ = std::make_unique<SurfaceReference>(std::move(s));
    if (o_.no_visual) return ok_status();
    SRCODEC_ASSIGN_OR_RETURN(VisualReference v, VisualReference::build(input_, o_.visual));
    visual_ = std::make_unique<VisualReference>(std::move(v));
    return ok_status();
  }
  const TriangleMesh& input() const { return input_; }
  void say(const std::string& line) const {
    if (!o_.quiet) std::cerr << "rd: " << line << std::endl;
  }
  // Distortion of `decoded` against the input, and the rate of `bytes`.
  Status measure(const TriangleMesh& decoded, uint64_t bytes, RdRow& row) const {
    SRCODEC_ASSIGN_OR_RETURN(SurfaceDistance d, surface_->distance_to(decoded));
    row.bytes = bytes;
    row.bpv = 8.0 * static_cast<double>(bytes) / static_cast<double>(input_.positions.size());
    row.psnr = d.psnr;
    row.rms = d.rms;
    row.hausdorff = d.hausdorff;
    if (visual_) {
      SRCODEC_ASSIGN_OR_RETURN(VisualDifference v, visual_->difference_to(decoded));
      row.normal_degrees = v.mean_normal_degrees;
      row.defect_share = v.defect_share;
      row.depth_psnr = v.depth_psnr;
      row.turned_over_share = v.turned_over_share;
    }
    say(row.codec + " " + row.setting + ": " + std::to_string(bytes) + " bytes, " + fixed(row.bpv, 3) + " bpv, " +
        fixed(row.psnr, 2) + " dB" +
        (visual_ ? ", defects " + fixed(100 * row.defect_share, 2) + "% of pixels, turned over " +
                       fixed(100 * row.turned_over_share, 3) + "% of the area"
                 : ""));
    return ok_status();
  }

 private:
  const RdCliOptions& o_;
  TriangleMesh input_;
  SurfaceDistanceOptions metric_;
  std::unique_ptr<SurfaceReference> surface_;
  std::unique_ptr<VisualReference> visual_;
};

// The files the sweep decodes, cut from one full stream.
class StreamCuts {
 public:
  StreamCuts(std::vector<uint8_t> full, bool truncate) : full_(std::move(full)), truncate_(truncate) {}

  Status init() {
    SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(full_.data(), full_.size()));
    if (truncate_) {
      SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> smallest, truncate_srm(full_, 0));
      minimum_ = smallest.size();
    } else {
      // Header, base mesh, creases and flags: the offset of the first segment.
      minimum_ = f.segments.empty() ? full_.size() : f.segments.front().offset;
    }
    return ok_status();
  }
  uint64_t minimum() const { return minimum_; }
  uint64_t full_size() const { return full_.size(); }

  // The largest file of at most `budget` bytes: truncate_srm_to_size, as in
  // `encode --bytes`, or the first `budget` bytes.
  StatusOr<std::vector<uint8_t>> within(uint64_t budget) const {
    if (!truncate_) return std::vector<uint8_t>(full_.begin(), full_.begin() + std::min(budget, full_size()));
    return truncate_srm_to_size(full_.data(), full_.size(), budget);
  }

 private:
  std::vector<uint8_t> full_;
  bool truncate_;
  uint64_t minimum_ = 0;
};

// `points` sizes from `lo` to `hi`, evenly spaced in log(bytes), distinct.
std::vector<uint64_t> log_spaced(uint64_t lo, uint64_t hi, int points) {
  std::vector<uint64_t> out;
  for (int i = 0; i < points; ++i) {
    const double t = points > 1 ? static_cast<double>(i) / (points - 1) : 1.0;
    const double v = std::exp(std::log(static_cast<double>(lo)) * (1 - t) + std::log(static_cast<double>(hi)) * t);
    out.push_back(i == 0 ? lo : (i == points - 1 ? hi : std::clamp<uint64_t>(std::llround(v), lo, hi)));
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// parse_srm + decode_srm of one file, timed as the median of 3 runs.
StatusOr<DecodedSrm> timed_decode(const std::vector<uint8_t>& file, bool prefix_read, double& ms) {
  std::vector<double> times;
  std::optional<DecodedSrm> decoded;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    SrmReadOptions read;
    if (prefix_read) read.max_bytes = file.size();
    SRCODEC_ASSIGN_OR_RETURN(SrmFile f, parse_srm(file.data(), file.size(), read));
    SRCODEC_ASSIGN_OR_RETURN(DecodedSrm d, decode_srm(f));
    times.push_back(ms_since(start));
    decoded = std::move(d);
  }
  std::sort(times.begin(), times.end());
  ms = times[1];
  return std::move(*decoded);
}

StatusOr<std::vector<RdRow>> srcodec_rows(const RdRun& run, const RdCliOptions& o) {
  SRCODEC_ASSIGN_OR_RETURN(RemeshOptions remesh_options, to_remesh_options(o.remesh));
  if (!o.quiet)
    remesh_options.progress = remesh_progress_lines([&run](const std::string& line) { run.say("remesh: " + line); });
  run.say("remeshing and encoding the full stream");
  const auto start = std::chrono::steady_clock::now();
  SRCODEC_ASSIGN_OR_RETURN(SemiRegularMesh srm, remesh(run.input(), remesh_options));
  SRCODEC_ASSIGN_OR_RETURN(EncodedSrm encoded, encode_srm(srm, run.input()));
  const double encode_ms = ms_since(start);
  const bool truncate = o.cut == "truncate";
  StreamCuts cuts(std::move(encoded.bytes), truncate);
  SRCODEC_RETURN_IF_ERROR(cuts.init());
  run.say("full stream " + std::to_string(cuts.full_size()) + " bytes in " + fixed(encode_ms / 1000, 2) +
          " s; smallest decodable file " + std::to_string(cuts.minimum()) + " bytes");
  std::vector<RdRow> rows;
  for (uint64_t budget : log_spaced(cuts.minimum(), cuts.full_size(), o.points)) {
    SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cuts.within(budget));
    RdRow row;
    row.codec = "srcodec";
    row.setting = (truncate ? "bytes=" : "prefix=") + std::to_string(budget);
    row.encode_ms = encode_ms;
    SRCODEC_ASSIGN_OR_RETURN(DecodedSrm d, timed_decode(file, !truncate, row.decode_ms));
    SRCODEC_RETURN_IF_ERROR(run.measure(d.mesh, file.size(), row).with_context(row.setting));
    rows.push_back(row);
  }
  return rows;
}

StatusOr<std::vector<RdRow>> draco_rows(const RdRun& run) {
  std::vector<RdRow> rows;
  for (int bits = kDracoMinBits; bits <= kDracoMaxBits; ++bits) {
    DracoOptions options;
    options.quantization_bits = bits;
    options.compression_level = kDracoLevel;
    SRCODEC_ASSIGN_OR_RETURN(DracoRoundTrip r, draco_round_trip(run.input(), options));
    RdRow row;
    row.codec = "draco";
    row.setting = "qp=" + std::to_string(bits);
    row.encode_ms = r.encode_ms;
    row.decode_ms = r.decode_ms;
    SRCODEC_RETURN_IF_ERROR(run.measure(r.decoded, r.encoded.size(), row).with_context("draco " + row.setting));
    rows.push_back(row);
  }
  return rows;
}

std::string csv_number(double v, const char* format) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  if (std::isnan(v)) return "nan";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

std::string to_csv(const std::vector<RdRow>& rows) {
  std::string s =
      "codec,setting,bytes,bpv,psnr,rms,hausdorff,encode_ms,decode_ms,normal_deg,defect_share,depth_psnr,"
      "turned_over_share\n";
  for (const RdRow& r : rows) {
    s += r.codec + "," + r.setting + "," + std::to_string(r.bytes) + "," + csv_number(r.bpv, "%.6f") + "," +
         csv_number(r.psnr, "%.4f") + "," + csv_number(r.rms, "%.9g") + "," + csv_number(r.hausdorff, "%.9g") + "," +
         csv_number(r.encode_ms, "%.3f") + "," + csv_number(r.decode_ms, "%.3f") + "," +
         csv_number(r.normal_degrees, "%.4f") + "," + csv_number(r.defect_share, "%.6f") + "," +
         csv_number(r.depth_psnr, "%.4f") + "," + csv_number(r.turned_over_share, "%.8f") + "\n";
  }
  return s;
}

RdCurve curve_of(const std::vector<RdRow>& rows, const std::string& codec) {
  RdCurve c;
  for (const RdRow& r : rows)
    if (r.codec == codec) c.push_back({static_cast<double>(r.bytes), r.psnr});
  return c;
}

double median_of(const std::vector<RdRow>& rows, const std::string& codec, double RdRow::*field) {
  std::vector<double> v;
  for (const RdRow& r : rows)
    if (r.codec == codec) v.push_back(r.*field);
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

struct CodecRange {
  size_t points = 0;  // rows, including dominated ones
  double min_bytes = 0, max_bytes = 0, min_psnr = 0, max_psnr = 0;
};

CodecRange range_of(const std::vector<RdRow>& rows, const std::string& codec) {
  CodecRange r;
  r.min_bytes = r.min_psnr = INFINITY;
  r.max_bytes = r.max_psnr = -INFINITY;
  for (const RdRow& row : rows) {
    if (row.codec != codec) continue;
    ++r.points;
    r.min_bytes = std::min(r.min_bytes, static_cast<double>(row.bytes));
    r.max_bytes = std::max(r.max_bytes, static_cast<double>(row.bytes));
    r.min_psnr = std::min(r.min_psnr, row.psnr);
    r.max_psnr = std::max(r.max_psnr, row.psnr);
  }
  return r;
}

struct Crossover {
  double psnr = 0;
  bool srcodec_cheaper_below = false;
};

// The visual figures of a point on a curve, interpolated between two rows.
struct Seen {
  double bytes = 0, normal_degrees = 0, defect_share = 0, turned_over_share = 0;
};

// The rows of one codec on its rd_front, by bytes; none when the visual
// columns are missing.
std::vector<const RdRow*> visual_front(const std::vector<RdRow>& rows, const std::string& codec) {
  std::vector<const RdRow*> front;
  for (const RdPoint& p : rd_front(curve_of(rows, codec)))
    for (const RdRow& r : rows)
      if (r.codec == codec && static_cast<double>(r.bytes) == p.rate && r.psnr == p.psnr) {
        if (!std::isfinite(r.normal_degrees)) return {};
        front.push_back(&r);
        break;
      }
  return front;
}

// `t` of the way from a to b, bytes in log scale (as rate_at_psnr reads them).
Seen between(const RdRow& a, const RdRow& b, double t) {
  const auto lerp = [t](double x, double y) { return x + t * (y - x); };
  Seen v;
  v.bytes = std::exp(lerp(std::log(static_cast<double>(a.bytes)), std::log(static_cast<double>(b.bytes))));
  v.normal_degrees = lerp(a.normal_degrees, b.normal_degrees);
  v.defect_share = lerp(a.defect_share, b.defect_share);
  v.turned_over_share = lerp(a.turned_over_share, b.turned_over_share);
  return v;
}

// Where the front reaches `psnr` (by PSNR) or `bytes` (by log bytes); nullopt outside it.
std::optional<Seen> seen_at(const std::vector<const RdRow*>& front, double psnr, double bytes) {
  for (size_t i = 0; i + 1 < front.size(); ++i) {
    const RdRow &a = *front[i], &b = *front[i + 1];
    if (bytes > 0) {
      const double la = std::log(static_cast<double>(a.bytes)), lb = std::log(static_cast<double>(b.bytes));
      if (std::log(bytes) >= la && std::log(bytes) <= lb) return between(a, b, (std::log(bytes) - la) / (lb - la));
    } else if (psnr >= a.psnr && psnr <= b.psnr) {
      return between(a, b, (psnr - a.psnr) / (b.psnr - a.psnr));
    }
  }
  return std::nullopt;
}

// srcodec where its curve reaches a PSNR, and Draco at the same bytes and
// at the same PSNR.
struct SeenAt {
  double psnr = 0;
  std::optional<Seen> srcodec, draco_same_bytes, draco_same_psnr;
};

struct RdSummary {
  CodecRange srcodec, draco;
  std::optional<BdRate> bd;
  std::string bd_error;
  std::vector<std::optional<double>> ratios;  // srcodec / draco bytes at kRatioPsnrs
  std::vector<Crossover> crossovers;
  std::vector<SeenAt> seen;  // at kRatioPsnrs; empty with --no-visual
  double srcodec_encode_ms = 0, draco_encode_ms = 0, srcodec_decode_ms = 0, draco_decode_ms = 0;
};

RdSummary summarize(const std::vector<RdRow>& rows) {
  RdSummary s;
  s.srcodec = range_of(rows, "srcodec");
  s.draco = range_of(rows, "draco");
  const RdCurve sc = curve_of(rows, "srcodec"), dc = curve_of(rows, "draco");
  StatusOr<BdRate> bd = bd_rate(dc, sc);
  if (bd.ok()) {
    s.bd = bd.value();
  } else {
    s.bd_error = bd.status().message();
  }
  for (double psnr : kRatioPsnrs) {
    const std::optional<double> a = rate_at_psnr(sc, psnr), b = rate_at_psnr(dc, psnr);
    s.ratios.push_back(a && b ? std::optional<double>(*a / *b) : std::nullopt);
  }
  const RdCurve fs = rd_front(sc), fd = rd_front(dc);
  for (double p : crossover_psnrs(sc, dc)) {
    // Which is cheaper just below the crossing.
    const double below = std::max(p - 0.01, std::max(fs.front().psnr, fd.front().psnr));
    const std::optional<double> a = rate_at_psnr(sc, below), b = rate_at_psnr(dc, below);
    s.crossovers.push_back({p, a && b && *a < *b});
  }
  const std::vector<const RdRow*> vs = visual_front(rows, "srcodec"), vd = visual_front(rows, "draco");
  if (!vs.empty() && !vd.empty()) {
    for (double psnr : kRatioPsnrs) {
      SeenAt e;
      e.psnr = psnr;
      e.srcodec = seen_at(vs, psnr, 0);
      if (e.srcodec) e.draco_same_bytes = seen_at(vd, 0, e.srcodec->bytes);
      e.draco_same_psnr = seen_at(vd, psnr, 0);
      s.seen.push_back(e);
    }
  }
  s.srcodec_encode_ms = median_of(rows, "srcodec", &RdRow::encode_ms);
  s.draco_encode_ms = median_of(rows, "draco", &RdRow::encode_ms);
  s.srcodec_decode_ms = median_of(rows, "srcodec", &RdRow::decode_ms);
  s.draco_decode_ms = median_of(rows, "draco", &RdRow::decode_ms);
  return s;
}

std::string percent(double fraction) { return (fraction >= 0 ? "+" : "") + fixed(100.0 * fraction, 1) + "%"; }

// Why there is no ratio at `psnr`: which codec does not reach it (or starts above it).
std::string missing_ratio_reason(const RdSummary& s, double psnr) {
  std::string why;
  for (const auto& [name, r] : {std::pair<const char*, const CodecRange&>{"srcodec", s.srcodec}, {"draco", s.draco}}) {
    if (r.max_psnr < psnr) why += std::string(why.empty() ? "" : ", ") + name + " reaches " + fixed(r.max_psnr, 1) + " dB at most";
    if (r.min_psnr > psnr) why += std::string(why.empty() ? "" : ", ") + name + " starts at " + fixed(r.min_psnr, 1) + " dB";
  }
  return "n/a (" + why + ")";
}

void print_summary(const RdCliOptions& o, size_t vertices, const RdSummary& s, const std::string& plot) {
  std::printf("rd %s (%zu vertices) -> %s/rd.csv%s\n", o.input.c_str(), vertices, o.out_dir.c_str(),
              plot.empty() ? " (no plot)" : (", " + plot).c_str());
  for (const auto& [name, r] : {std::pair<const char*, const CodecRange&>{"srcodec", s.srcodec}, {"draco", s.draco}})
    std::printf("  %-7s %zu points, %.0f..%.0f bytes (%.3f..%.3f bpv), %.2f..%.2f dB\n", name, r.points, r.min_bytes,
                r.max_bytes, 8 * r.min_bytes / vertices, 8 * r.max_bytes / vertices, r.min_psnr, r.max_psnr);
  if (s.bd) {
    std::printf("  BD-rate srcodec vs draco: %s over %.2f..%.2f dB (cubic fit, VCEG-M33; piecewise-linear: %s)\n",
                percent(s.bd->delta).c_str(), s.bd->psnr_low, s.bd->psnr_high, percent(s.bd->linear_delta).c_str());
    const double width = s.bd->psnr_high - s.bd->psnr_low;
    if (width < kNarrowOverlapDb)
      std::printf("  caution: the curves share only %.2f dB of PSNR; this BD-rate says little\n", width);
    if (std::abs(s.bd->delta - s.bd->linear_delta) > kFitDisagreement)
      std::printf("  caution: the cubic fit and the piecewise-linear reading differ by %.1f points: a curve bends "
                  "more than a cubic follows (see the plot)\n",
                  100.0 * std::abs(s.bd->delta - s.bd->linear_delta));
  } else {
    std::printf("  BD-rate srcodec vs draco: n/a (%s)\n", s.bd_error.c_str());
  }
  std::string ratios;
  for (size_t i = 0; i < s.ratios.size(); ++i)
    ratios += std::string(i ? "; " : "") + fixed(kRatioPsnrs[i], 0) + " dB " +
              (s.ratios[i] ? fixed(*s.ratios[i], 3) : missing_ratio_reason(s, kRatioPsnrs[i]));
  std::printf("  bytes srcodec/draco: %s\n", ratios.c_str());
  if (s.crossovers.empty()) {
    std::printf("  crossover: none in the shared PSNR range\n");
  } else {
    for (const Crossover& c : s.crossovers)
      std::printf("  crossover: %.2f dB (%s smaller below, %s above)\n", c.psnr,
                  c.srcodec_cheaper_below ? "srcodec" : "draco", c.srcodec_cheaper_below ? "draco" : "srcodec");
  }
  for (const SeenAt& e : s.seen) {
    if (!e.srcodec) {
      std::printf("  seen at %.0f dB: n/a (srcodec's curve does not reach it)\n", e.psnr);
      continue;
    }
    const auto line = [&](const char* what, const Seen& d) {
      std::printf("  seen at %.0f dB, srcodec/draco %s: normal angle %.2f/%.2f deg, defect pixels %.3f/%.3f%%, "
                  "turned over %.4f/%.4f%%\n",
                  e.psnr, what, e.srcodec->normal_degrees, d.normal_degrees, 100 * e.srcodec->defect_share,
                  100 * d.defect_share, 100 * e.srcodec->turned_over_share, 100 * d.turned_over_share);
    };
    if (e.draco_same_bytes) {
      line(("at " + fixed(e.srcodec->bytes, 0) + " bytes").c_str(), *e.draco_same_bytes);
    } else {
      std::printf("  seen at %.0f dB at equal bytes: n/a (srcodec needs %.0f bytes; draco's files are %.0f..%.0f)\n",
                  e.psnr, e.srcodec->bytes, s.draco.min_bytes, s.draco.max_bytes);
    }
    if (e.draco_same_psnr)
      line(("at equal PSNR (draco " + fixed(e.draco_same_psnr->bytes, 0) + " bytes)").c_str(), *e.draco_same_psnr);
  }
  std::printf("  time srcodec/draco: encode %.1fx (remesh + encode %.0f ms vs median %.1f ms), decode %.1fx "
              "(median %.1f ms vs %.1f ms)\n",
              s.srcodec_encode_ms / s.draco_encode_ms, s.srcodec_encode_ms, s.draco_encode_ms,
              s.srcodec_decode_ms / s.draco_decode_ms, s.srcodec_decode_ms, s.draco_decode_ms);
}

JsonWriter range_json(const CodecRange& r) {
  JsonWriter j;
  j.field("points", r.points)
      .field("min_bytes", r.min_bytes)
      .field("max_bytes", r.max_bytes)
      .field("min_psnr", r.min_psnr)
      .field("max_psnr", r.max_psnr);
  return j;
}

std::string summary_json(const RdCliOptions& o, size_t vertices, const RdSummary& s, const std::string& plot) {
  JsonWriter j;
  j.field("input", o.input).field("input_vertices", vertices).field("csv", o.out_dir + "/rd.csv");
  plot.empty() ? j.null_field("plot") : j.field("plot", plot);
  j.object("srcodec", range_json(s.srcodec)).object("draco", range_json(s.draco));
  if (s.bd) {
    j.field("bd_rate", s.bd->delta)
        .field("bd_rate_linear", s.bd->linear_delta)
        .field("bd_psnr_low", s.bd->psnr_low)
        .field("bd_psnr_high", s.bd->psnr_high)
        .field("bd_narrow_overlap", s.bd->psnr_high - s.bd->psnr_low < kNarrowOverlapDb)
        .field("bd_fit_disagrees", std::abs(s.bd->delta - s.bd->linear_delta) > kFitDisagreement);
  } else {
    j.null_field("bd_rate").field("bd_error", s.bd_error);
  }
  for (size_t i = 0; i < s.ratios.size(); ++i) {
    const std::string key = "bytes_ratio_" + fixed(kRatioPsnrs[i], 0) + "db";
    s.ratios[i] ? j.field(key, *s.ratios[i]) : j.null_field(key);
  }
  std::vector<JsonWriter> crossings;
  for (const Crossover& c : s.crossovers) {
    JsonWriter x;
    x.field("psnr", c.psnr).field("cheaper_below", c.srcodec_cheaper_below ? "srcodec" : "draco");
    crossings.push_back(x);
  }
  std::vector<JsonWriter> seen;
  for (const SeenAt& e : s.seen) {
    JsonWriter x;
    x.field("psnr", e.psnr);
    for (const auto& [name, v] : {std::pair<const char*, const std::optional<Seen>&>{"srcodec", e.srcodec},
                                  {"draco_same_bytes", e.draco_same_bytes},
                                  {"draco_same_psnr", e.draco_same_psnr}}) {
      if (!v) {
        x.null_field(name);
        continue;
      }
      JsonWriter f;
      f.field("bytes", v->bytes)
          .field("normal_degrees", v->normal_degrees)
          .field("defect_share", v->defect_share)
          .field("turned_over_share", v->turned_over_share);
      x.object(name, f);
    }
    seen.push_back(x);
  }
  j.array("seen_at", seen);
  j.array("crossovers", crossings)
      .field("srcodec_encode_ms", s.srcodec_encode_ms)
      .field("draco_encode_ms", s.draco_encode_ms)
      .field("srcodec_decode_ms", s.srcodec_decode_ms)
      .field("draco_decode_ms", s.draco_decode_ms)
      .field("encode_time_ratio", s.srcodec_encode_ms / s.draco_encode_ms)
      .field("decode_time_ratio", s.srcodec_decode_ms / s.draco_decode_ms);
  return j.str();
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  return last;
}

// Runs tools/rd_plot.py on the CSV; "" when the plot was drawn, else why not.
std::string draw_plot(const std::string& dir, const std::string& title) {
  const char* env = std::getenv("SRCODEC_PLOT_SCRIPT");
  const std::string script = env && *env ? env : std::string(SRCODEC_SOURCE_DIR) + "/tools/rd_plot.py";
  if (!std::filesystem::exists(script)) return "plot script " + script + " not found (set SRCODEC_PLOT_SCRIPT)";
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string log = dir + "/rd_plot.log";
  const std::string command = python + " " + shell_quote(script) + " " + shell_quote(dir + "/rd.csv") + " -o " +
                              shell_quote(dir + "/rd.png") + " --title " + shell_quote(title) + " >" +
                              shell_quote(log) + " 2>&1 </dev/null";
  const int status = std::system(command.c_str());
  std::error_code ignored;
  if (status == 0) {
    std::filesystem::remove(log, ignored);
    return "";
  }
  std::filesystem::remove(dir + "/rd.png", ignored);  // an older run's plot would not match rd.csv
  const std::string reason = last_line(log);
  return python + " " + script + " failed" + (reason.empty() ? "" : ": " + reason) + " (see " + log + ")";
}

Status run_rd(const RdCliOptions& o) {
  if (o.cut != "truncate" && o.cut != "prefix") return invalid_argument("--cut " + o.cut + ": use truncate or prefix");
  SRCODEC_RETURN_IF_ERROR(to_remesh_options(o.remesh).status());
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh input, read_triangle_mesh(o.input));
  std::error_code error;
  std::filesystem::create_directories(o.out_dir, error);
  if (error || !std::filesystem::is_directory(o.out_dir))
    return io_error("cannot create the output folder " + o.out_dir + (error ? ": " + error.message() : ""));
  RdRun run(o, std::move(input));
  run.say(o.input + ": " + std::to_string(run.input().positions.size()) + " vertices");
  SRCODEC_RETURN_IF_ERROR(run.init());
  SRCODEC_ASSIGN_OR_RETURN(std::vector<RdRow> rows, srcodec_rows(run, o));
  SRCODEC_ASSIGN_OR_RETURN(std::vector<RdRow> draco, draco_rows(run));
  rows.insert(rows.end(), draco.begin(), draco.end());
  SRCODEC_RETURN_IF_ERROR(write_file_atomically(o.out_dir + "/rd.csv", to_csv(rows)));
  std::string plot;
  if (o.no_plot) {
    std::error_code ignored;
    std::filesystem::remove(o.out_dir + "/rd.png", ignored);  // an older run's plot would not match rd.csv
  } else {
    const std::string failure = draw_plot(o.out_dir, std::filesystem::path(o.input).filename().string());
    if (failure.empty()) {
      plot = o.out_dir + "/rd.png";
    } else {
      std::cerr << "rd: warning: no plot: " << failure << "; rd.csv and the summary are written\n";
    }
  }
  const RdSummary summary = summarize(rows);
  const size_t vertices = run.input().positions.size();
  const std::string json = summary_json(o, vertices, summary, plot);
  SRCODEC_RETURN_IF_ERROR(write_file_atomically(o.out_dir + "/summary.json", json + "\n"));
  if (o.json) {
    std::cout << json << "\n";
  } else {
    print_summary(o, vertices, summary, plot);
  }
  return ok_status();
}

}  // namespace

Command add_rd_command(CommandLine& cli) {
  auto o = std::make_shared<RdCliOptions>();
  Subcommand& cmd = cli.add_command("rd", "Rate-distortion curves of srcodec and Draco on one mesh, with BD-rate");
  cmd.positional("mesh", o->input, "Input mesh (OBJ, PLY, OFF, STL)");
  cmd.option("-o,--output", o->out_dir, "Folder for rd.csv, rd.png and summary.json (created if missing)").required();
  add_remesh_flags(cmd, o->remesh);
  cmd.option("--points", o->points, "srcodec rates, log-spaced from the base mesh alone to the whole stream")
      .range(2, 100)
      .show_default();
  cmd.option("--samples", o->samples, "Samples per surface for every distance figure (seeded)")
      .range(size_t{1000}, size_t{100000000})
      .show_default();
  cmd.option("--cut", o->cut,
             "srcodec files: truncate (as `encode --bytes` writes them) or prefix (the whole stream's first bytes)")
      .one_of({"truncate", "prefix"})
      .show_default();
  add_visual_flags(cmd, o->visual, o->no_visual, "Surface distance only (the visual columns of rd.csv are nan)");
  cmd.flag("--json", o->json, "Print the summary as one JSON object");
  cmd.flag("-q,--quiet", o->quiet, "No progress lines on stderr");
  cmd.flag("--no-plot", o->no_plot, "Do not call tools/rd_plot.py");
  return {&cmd, [o] { return run_rd(*o); }};
}

}  // namespace srcodec
