// The public encoder (<srcodec/encoder.h>) as a library user meets it: the
// same file as `srcodec encode` at the defaults, each rate kept, and a
// Status for every kind of bad mesh or option.
#include <srcodec/srcodec.h>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

Mesh sample_mesh() {
  StatusOr<Mesh> mesh = read_mesh(test::source_path("data/spot.obj"));
  EXPECT_TRUE(mesh.ok()) << mesh.status().message();
  return mesh.ok() ? *mesh : Mesh{};
}

// A quick encode for the rate tests: two levels.
EncodeOptions quick(Rate rate) {
  EncodeOptions o;
  o.levels = 2;
  o.rate = rate;
  return o;
}

void expect_invalid(const StatusOr<std::vector<uint8_t>>& r, const std::string& words) {
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find(words), std::string::npos) << r.status().message();
}

TEST(EncoderApi, DefaultsWriteWhatTheCommandWrites) {
  std::vector<std::string> stages;
  EncodeOptions options;
  options.progress = [&](const EncodeProgress& p) { stages.push_back(p.stage); };
  EncodeReport report;
  StatusOr<std::vector<uint8_t>> file = encode(sample_mesh(), options, &report);
  ASSERT_TRUE(file.ok()) << file.status().message();
  // tests/data/spot_default.srm is `srcodec encode data/spot.obj` (also pinned
  // by sample_pin_test): the library and the command are one encoder.
  StatusOr<std::string> expected = read_file_bytes(test::source_path("tests/data/spot_default.srm"));
  ASSERT_TRUE(expected.ok());
  EXPECT_EQ(std::string(file->begin(), file->end()), *expected);
  ASSERT_GE(stages.size(), 8u);
  EXPECT_NE(std::find(stages.begin(), stages.end(), "base mesh"), stages.end());
  EXPECT_EQ(std::count(stages.begin(), stages.end(), "level"), 4);
  EXPECT_EQ(std::vector<std::string>(stages.end() - 4, stages.end()),
            (std::vector<std::string>{"remesh", "code", "rate", "measure"}));
  EXPECT_EQ(report.bytes, file->size());
  EXPECT_GE(report.bytes, report.minimum_bytes);
  EXPECT_LE(report.bytes, report.full_stream_bytes);
  EXPECT_EQ(report.levels, 4);
  EXPECT_GT(report.psnr, 40.0);
  StatusOr<Decoded> decoded = decode(file->data(), file->size());
  ASSERT_TRUE(decoded.ok()) << decoded.status().message();
  EXPECT_EQ(decoded->level, 4);
}

// The encoder's parallel parts split work, never a sum or a choice: on one
// thread it writes the file it writes on all of them (the pinned default,
// made on two cores).
TEST(EncoderApi, OneThreadWritesTheSameFile) {
  const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  StatusOr<std::vector<uint8_t>> file = encode(sample_mesh(), EncodeOptions{});
  ASSERT_TRUE(file.ok()) << file.status().message();
  StatusOr<std::string> expected = read_file_bytes(test::source_path("tests/data/spot_default.srm"));
  ASSERT_TRUE(expected.ok());
  EXPECT_EQ(std::string(file->begin(), file->end()), *expected);
}

TEST(EncoderApi, KeepsTheRateAskedFor) {
  const Mesh mesh = sample_mesh();
  EncodeReport report;
  StatusOr<std::vector<uint8_t>> psnr = encode(mesh, quick(Rate::psnr(45.0)), &report);
  ASSERT_TRUE(psnr.ok()) << psnr.status().message();
  EXPECT_GE(report.psnr, 45.0);
  EXPECT_LT(report.bytes, report.full_stream_bytes);

  StatusOr<std::vector<uint8_t>> bytes = encode(mesh, quick(Rate::bytes(1200)), &report);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  EXPECT_LE(bytes->size(), 1200u);
  EXPECT_GT(bytes->size(), 1000u);

  const double bpv = 2.0;
  StatusOr<std::vector<uint8_t>> per_vertex = encode(mesh, quick(Rate::bits_per_vertex(bpv)), &report);
  ASSERT_TRUE(per_vertex.ok()) << per_vertex.status().message();
  EXPECT_LE(8.0 * per_vertex->size(), bpv * mesh.vertex_count());
}

TEST(EncoderApi, SaysWhenTheRateCannotBeMet) {
  const Mesh mesh = sample_mesh();
  expect_invalid(encode(mesh, quick(Rate::psnr(400.0))), "out of reach");
  expect_invalid(encode(mesh, quick(Rate::bytes(40))), "below the");
}

TEST(EncoderApi, RefusesOptionsOutOfRange) {
  const Mesh mesh = sample_mesh();
  const auto with = [](auto change) {
    EncodeOptions o;
    change(o);
    return o;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.levels = 13; })), "levels 13");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.levels = -2; })), "levels -2");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.tangential_factor = 0.1; })), "tangential_factor");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.base_bits = 30; })), "base_bits 30");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.raw_planes = -1; })), "raw_planes");
  expect_invalid(encode(mesh, with([&](EncodeOptions& o) { o.rate = Rate::psnr(nan); })), "PSNR");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.rate = Rate::bits_per_vertex(-1); })), "bits per vertex");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.rate = Rate{Rate::Kind::kBytes, 2.5}; })), "whole number");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) {
                   o.adaptivity = Adaptivity::kMeasuredError;
                   o.max_loss_db = 0;
                 })),
                 "max_loss_db");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) {
                   o.adaptivity = Adaptivity::kVertexCount;
                   o.threshold = -1;
                 })),
                 "threshold");
  expect_invalid(encode(mesh, with([](EncodeOptions& o) { o.base_vertices = 1u << 30; })), "base");
}

TEST(EncoderApi, RefusesBadMeshes) {
  Mesh mesh = sample_mesh();
  Mesh ragged = mesh;
  ragged.positions.pop_back();
  expect_invalid(encode(ragged), "not a multiple of 3");
  Mesh out_of_range = mesh;
  out_of_range.triangles[4] = static_cast<uint32_t>(mesh.vertex_count());
  expect_invalid(encode(out_of_range), "triangle 1 uses vertex");
  Mesh not_finite = mesh;
  not_finite.positions[7] = std::numeric_limits<double>::infinity();
  expect_invalid(encode(not_finite), "vertex 2");
  expect_invalid(encode(Mesh{}), "no triangle");
  Mesh flat{{0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2}};
  expect_invalid(encode(flat), "no triangle");
}

}  // namespace
}  // namespace srcodec
