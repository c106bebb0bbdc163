// Rate control over an embedded .srm stream (codec/rate_control.h): the
// knee `srcodec encode` keeps with no rate option.
#include "codec/rate_control.h"

#include <gtest/gtest.h>

#include "codec/srm_codec.h"
#include "format/mesh_files/mesh_io.h"
#include "remesh/remesher.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

// The whole stream of `input` remeshed with `options`.
std::vector<uint8_t> whole_stream(const TriangleMesh& input, const RemeshOptions& options) {
  StatusOr<SemiRegularMesh> srm = remesh(input, options);
  EXPECT_TRUE(srm.ok()) << srm.status().message();
  if (!srm.ok()) return {};
  StatusOr<EncodedSrm> encoded = encode_srm(srm.value(), input);
  EXPECT_TRUE(encoded.ok()) << encoded.status().message();
  return encoded.ok() ? encoded->bytes : std::vector<uint8_t>{};
}

// PSNR gained per bit per input vertex from file `a` to file `b`.
double slope(const Knee& a, double b_psnr, uint64_t b_bytes, size_t vertices) {
  return (b_psnr - a.psnr) / (8.0 * (static_cast<double>(b_bytes) - static_cast<double>(a.file_bytes)) / vertices);
}

TEST(RateControl, KneeKeepsTheSteepPartOfTheCurve) {
  StatusOr<TriangleMesh> input = read_triangle_mesh(test::source_path("data/spot.obj"));
  ASSERT_TRUE(input.ok()) << input.status().message();
  RemeshOptions options;
  options.levels = 2;  // a knee already (and a quarter of 3 levels' time under the sanitizers)
  const std::vector<uint8_t> stream = whole_stream(input.value(), options);
  ASSERT_FALSE(stream.empty());
  const StreamCutter cutter(input.value(), stream);
  const size_t n = input->positions.size();
  StatusOr<Knee> knee = knee_of_stream(cutter, n);
  ASSERT_TRUE(knee.ok()) << knee.status().message();
  ASSERT_FALSE(knee->whole_stream);
  ASSERT_GT(knee->segment_bytes, 0u);
  EXPECT_GT(knee->cuts, 3);
  EXPECT_EQ(cutter.cut(knee->segment_bytes)->size(), knee->file_bytes);
  EXPECT_DOUBLE_EQ(cutter.psnr(knee->segment_bytes, kRateControlSamples).value(), knee->psnr);
  // Measured apart from the ladder: over two steps (a file 1.5625 times as
  // large) before the knee the curve climbs faster than kKneeDbPerBpv, over
  // two steps after it and on to the whole stream slower.
  const auto cut_within = [&](double bytes) {
    Knee c;
    c.segment_bytes = cutter.segment_bytes_within(static_cast<uint64_t>(bytes)).value();
    c.file_bytes = cutter.cut(c.segment_bytes)->size();
    c.psnr = cutter.psnr(c.segment_bytes, kRateControlSamples).value();
    return c;
  };
  const Knee before = cut_within(knee->file_bytes / (kKneeCutRatio * kKneeCutRatio));
  const Knee after = cut_within(knee->file_bytes * kKneeCutRatio * kKneeCutRatio);
  ASSERT_GT(knee->file_bytes, before.file_bytes);
  EXPECT_GT(slope(before, knee->psnr, knee->file_bytes, n), kKneeDbPerBpv);
  EXPECT_LT(slope(knee.value(), after.psnr, after.file_bytes, n), kKneeDbPerBpv);
  const double whole = whole_stream_psnr(cutter).value();
  EXPECT_LT(slope(knee.value(), whole, stream.size(), n), kKneeDbPerBpv);
  EXPECT_GT(whole, knee->psnr);
  // Deterministic.
  StatusOr<Knee> again = knee_of_stream(cutter, n);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->segment_bytes, knee->segment_bytes);
}

// The estimate the knee search walks on (codec/cut_estimate.h) against the
// metric, on every cut of the ladder: of the right size everywhere (within
// 1.5 dB; it is closest near the whole stream, where knees lie), the
// measure itself for the whole stream, and the knee it leads to is the one
// the metric alone gives.
TEST(RateControl, EstimateLeadsToTheMetricsKnee) {
  for (const char* mesh : {"data/spot.obj", "data/bunny_npm.obj"}) {
    SCOPED_TRACE(mesh);
    StatusOr<TriangleMesh> input = read_triangle_mesh(test::source_path(mesh));
    ASSERT_TRUE(input.ok()) << input.status().message();
    RemeshOptions options;
    options.levels = 2;
    const std::vector<uint8_t> stream = whole_stream(input.value(), options);
    ASSERT_FALSE(stream.empty());
    const StreamCutter cutter(input.value(), stream);
    const size_t n = input->positions.size();
    // The ladder knee_of_stream places, every cut measured.
    std::vector<Knee> ladder;
    for (;;) {
      Knee c = next_ladder_cut(cutter, ladder.empty() ? nullptr : &ladder.back()).value();
      c.psnr = cutter.psnr(c.segment_bytes, kRateControlSamples).value();
      const double estimated = cutter.estimated_psnr(c.segment_bytes).value();
      EXPECT_NEAR(estimated, c.psnr, 1.5) << "cut of " << c.file_bytes << " bytes";
      ladder.push_back(c);
      if (c.segment_bytes >= cutter.segment_bytes()) {
        EXPECT_DOUBLE_EQ(estimated, c.psnr);
        break;
      }
    }
    ASSERT_GT(ladder.size(), 5u);
    size_t k = 0;
    for (; k + 1 < ladder.size(); ++k) {
      const size_t ahead = std::min(k + 2, ladder.size() - 1);
      if (!(ladder[ahead].psnr - ladder[k].psnr >= knee_gain_needed(ladder[k], ladder[ahead], n))) break;
    }
    StatusOr<Knee> knee = knee_of_stream(cutter, n);
    ASSERT_TRUE(knee.ok()) << knee.status().message();
    EXPECT_EQ(knee->segment_bytes, ladder[k].segment_bytes);
    EXPECT_DOUBLE_EQ(knee->psnr, ladder[k].psnr);
    EXPECT_LT(knee->cuts, static_cast<int>(ladder.size())) << "the estimate spares no measure";
  }
}

TEST(RateControl, KneeOfAStreamWithNoLevelsIsTheWholeStream) {
  // An octahedron as its own base mesh: nothing to refine, nothing to trade.
  // (Its edges, all creases, would be kept and coded: a chunk this
  // arithmetic of segments is not about.)
  TriangleMesh octahedron;
  octahedron.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  octahedron.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  RemeshOptions options;
  options.levels = 0;
  options.base_vertices = 6;
  options.oversample = 0;
  options.creases = CreaseMode::kIgnore;
  const std::vector<uint8_t> stream = whole_stream(octahedron, options);
  ASSERT_FALSE(stream.empty());
  const StreamCutter cutter(octahedron, stream);
  StatusOr<Knee> knee = knee_of_stream(cutter, octahedron.positions.size());
  ASSERT_TRUE(knee.ok()) << knee.status().message();
  EXPECT_TRUE(knee->whole_stream);
  EXPECT_EQ(knee->segment_bytes, cutter.segment_bytes());
  EXPECT_EQ(knee->file_bytes, stream.size());
  EXPECT_FALSE(knee_of_stream(cutter, 0).ok()) << "no input vertices: an error, not a division by zero";
}

// segment_bytes_within (truncate_srm_to_size) keeps the most segment bytes
// whose file fits, and refuses a budget below the smallest file.
TEST(RateControl, SegmentBytesWithinIsTheMostThatFits) {
  const TriangleMesh sphere = test::icosphere(3, 1.0);
  RemeshOptions options;
  options.levels = 1;
  const std::vector<uint8_t> stream = whole_stream(sphere, options);
  ASSERT_FALSE(stream.empty());
  const StreamCutter cutter(sphere, stream);
  ASSERT_GT(cutter.segment_bytes(), 0u);
  const uint64_t smallest = cutter.cut(0)->size();
  for (uint64_t budget : {smallest, smallest + 7, (smallest + stream.size()) / 2, uint64_t{stream.size()}}) {
    const StatusOr<uint64_t> kept = cutter.segment_bytes_within(budget);
    ASSERT_TRUE(kept.ok()) << kept.status().message();
    EXPECT_LE(cutter.cut(*kept)->size(), budget);
    if (*kept < cutter.segment_bytes()) {
      EXPECT_GT(cutter.cut(*kept + 1)->size(), budget);
    }
  }
  EXPECT_EQ(cutter.segment_bytes_within(stream.size()).value(), cutter.segment_bytes());
  EXPECT_FALSE(cutter.segment_bytes_within(smallest - 1).ok());
}

}  // namespace
}  // namespace srcodec
