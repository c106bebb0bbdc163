// How the default rate's knee search (codec/rate_control.h) fares with the
// cut estimate (codec/cut_estimate.h) against measuring every cut. For each
// mesh: the default remesh and its whole stream, then the ladder of cuts
// knee_of_stream places, each cut's estimated and measured PSNR, the knee
// each gives alone, and the knee knee_of_stream keeps; then knee_of_stream
// against the search by the metric alone (every cut measured up to its knee's
// two steps, two cuts at a time), timed alternately (median of --runs, and
// the median of the per-run ratios).
// Usage: knee_estimate MESH... [--runs N]
// Markdown on stdout (one table of all meshes; --ladder adds each mesh's
// cuts), progress on stderr.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <tbb/parallel_invoke.h>

#include "codec/rate_control.h"
#include "codec/srm_codec.h"
#include "format/mesh_files/mesh_io.h"
#include "remesh/remesher.h"

namespace {

using namespace srcodec;

template <class T>
T value_or_exit(StatusOr<T> s, const std::string& what) {
  if (!s.ok()) {
    std::fprintf(stderr, "%s: %s\n", what.c_str(), s.status().message().c_str());
    std::exit(1);
  }
  return std::move(s).value();
}

// A cut of the ladder with both its PSNRs.
struct Rung : Knee {
  double estimated = 0, measured = 0;
};

// The ladder knee_of_stream places: from the smallest file, each file
// kKneeCutRatio times the last, to the whole stream.
std::vector<Rung> ladder_of(const StreamCutter& cutter) {
  std::vector<Rung> ladder;
  for (;;) {
    Rung r;
    static_cast<Knee&>(r) = value_or_exit(next_ladder_cut(cutter, ladder.empty() ? nullptr : &ladder.back()), "cut");
    ladder.push_back(r);
    if (r.segment_bytes >= cutter.segment_bytes()) return ladder;
  }
}

// The rule of knee_of_stream over a ladder whose PSNRs are all known.
size_t knee_by(const std::vector<Rung>& ladder, size_t vertices, double Rung::*psnr) {
  for (size_t k = 0; k + 1 < ladder.size(); ++k) {
    const size_t ahead = std::min(k + 2, ladder.size() - 1);
    if (!(ladder[ahead].*psnr - ladder[k].*psnr >= knee_gain_needed(ladder[k], ladder[ahead], vertices))) return k;
  }
  return ladder.size() - 1;
}

double seconds_of(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string name_of(const std::string& path) {
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes;
  int runs = 3;
  bool show_ladder = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--ladder") {
      show_ladder = true;
    } else {
      meshes.push_back(a);
    }
  }
  if (meshes.empty()) {
    std::fprintf(stderr, "usage: knee_estimate MESH... [--runs N] [--ladder]\n");
    return 2;
  }
  std::printf("| mesh | cuts | largest \\|estimate - measure\\| (dB), all cuts / last 6 | largest two-step gain "
              "difference (dB) | knee: estimate alone | "
              "knee: metric alone | knee kept (cuts measured) | s: metric alone / knee_of_stream | ratio |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::string ladders;
  for (const std::string& path : meshes) {
    std::fprintf(stderr, "%s: remesh and encode ...\n", path.c_str());
    const TriangleMesh input = value_or_exit(read_triangle_mesh(path), path);
    const SemiRegularMesh srm = value_or_exit(remesh(input, RemeshOptions{}), path + ": remesh");
    const std::vector<uint8_t> stream = value_or_exit(encode_srm(srm, input), path + ": encode").bytes;
    const size_t n = input.positions.size();

    std::vector<double> measured_s, kept_s, ratios;
    Knee kept;
    std::vector<Rung> ladder;
    for (int r = 0; r < runs; ++r) {
      std::fprintf(stderr, "%s: run %d of %d\n", path.c_str(), r + 1, runs);
      double all = 0, one = 0;
      // The search by the metric alone: every cut measured,
      // two at a time, until its knee's two steps are measured; then the
      // rest of the ladder, untimed, for the table.
      const auto every_cut = [&] {
        const StreamCutter cutter(input, stream);  // a new cutter: nothing kept from the other side
        const auto start = std::chrono::steady_clock::now();
        ladder = ladder_of(cutter);
        const auto measure_pair = [&](size_t k) {
          tbb::parallel_invoke(
              [&] { ladder[k].measured = value_or_exit(cutter.psnr(ladder[k].segment_bytes, kRateControlSamples), "measure"); },
              [&] {
                if (k + 1 < ladder.size())
                  ladder[k + 1].measured =
                      value_or_exit(cutter.psnr(ladder[k + 1].segment_bytes, kRateControlSamples), "measure");
              });
        };
        size_t measured = 0;
        for (size_t k = 0;; ++k) {
          const size_t ahead = std::min(k + 2, ladder.size() - 1);
          for (; measured <= ahead; measured += 2) measure_pair(measured);
          if (ahead == k) break;
          if (!(ladder[ahead].measured - ladder[k].measured >= knee_gain_needed(ladder[k], ladder[ahead], n))) break;
        }
        all = seconds_of(start);
        for (; measured < ladder.size(); measured += 2) measure_pair(measured);
        for (Rung& rung : ladder) rung.estimated = value_or_exit(cutter.estimated_psnr(rung.segment_bytes), "estimate");
      };
      const auto knee_search = [&] {
        const StreamCutter cutter(input, stream);
        const auto start = std::chrono::steady_clock::now();
        kept = value_or_exit(knee_of_stream(cutter, n), "knee");
        one = seconds_of(start);
      };
      if (r % 2 == 0) {
        every_cut();
        knee_search();
      } else {
        knee_search();
        every_cut();
      }
      measured_s.push_back(all);
      kept_s.push_back(one);
      ratios.push_back(all / one);
    }
    double worst = 0, worst_top = 0, worst_gain = 0;
    for (size_t k = 0; k < ladder.size(); ++k) {
      const double d = std::abs(ladder[k].estimated - ladder[k].measured);
      worst = std::max(worst, d);
      if (k + 6 >= ladder.size()) worst_top = std::max(worst_top, d);
      const size_t ahead = std::min(k + 2, ladder.size() - 1);
      const double gain_error = (ladder[ahead].estimated - ladder[k].estimated) -
                                (ladder[ahead].measured - ladder[k].measured);
      worst_gain = std::max(worst_gain, std::abs(gain_error));
    }
    const size_t by_estimate = knee_by(ladder, n, &Rung::estimated);
    const size_t by_metric = knee_by(ladder, n, &Rung::measured);
    size_t kept_k = 0;
    while (kept_k < ladder.size() && ladder[kept_k].segment_bytes != kept.segment_bytes) ++kept_k;
    const auto cut_text = [&](size_t k) {
      char t[80];
      std::snprintf(t, sizeof t, "%llu B, %.2f dB", static_cast<unsigned long long>(ladder[k].file_bytes),
                    ladder[k].measured);
      return std::string(t);
    };
    std::printf("| %s | %zu | %.2f / %.2f | %.2f | %s | %s | %s (%d) | %.2f / %.2f | %.2fx |\n",
                name_of(path).c_str(), ladder.size(), worst, worst_top, worst_gain, cut_text(by_estimate).c_str(), cut_text(by_metric).c_str(),
                kept_k < ladder.size() ? cut_text(kept_k).c_str() : "not on the ladder", kept.cuts, median(measured_s),
                median(kept_s), median(ratios));
    std::fflush(stdout);
    if (show_ladder) {
      ladders += "\n" + name_of(path) + "\n\n| cut | file bytes | estimated dB | measured dB |\n|---:|---:|---:|---:|\n";
      for (size_t k = 0; k < ladder.size(); ++k) {
        char line[120];
        std::snprintf(line, sizeof line, "| %zu | %llu | %.3f | %.3f |\n", k,
                      static_cast<unsigned long long>(ladder[k].file_bytes), ladder[k].estimated, ladder[k].measured);
        ladders += line;
      }
    }
  }
  std::printf("%s", ladders.c_str());
  return 0;
}
