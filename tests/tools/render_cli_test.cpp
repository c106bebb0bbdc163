// `srcodec render` as a user meets it: a PNG of the right size, one-line
// errors with a non-zero exit, and no output left behind by a failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string>

#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::run_srcodec;
const auto q = test::shell_quote;

// Width and height from a PNG's header, or -1, -1 when it is not one.
std::pair<int64_t, int64_t> png_size(const std::string& bytes) {
  static const std::string signature = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 24 || bytes.compare(0, 8, signature) != 0 || bytes.compare(12, 4, "IHDR") != 0) return {-1, -1};
  const auto big_endian = [&](size_t at) {
    int64_t v = 0;
    for (size_t i = 0; i < 4; ++i) v = v * 256 + static_cast<uint8_t>(bytes[at + i]);
    return v;
  };
  return {big_endian(16), big_endian(20)};
}

void expect_one_line_error(const test::CommandResult& r, int exit_code, const std::string& what) {
  EXPECT_EQ(r.exit_code, exit_code) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(what), std::string::npos) << r.err;
}

TEST(RenderCli, WritesOnePngOfEveryPanelSideBySide) {
  test::ScratchDir dir;
  const std::string spot = test::source_path("data/spot.obj"), bunny = test::source_path("data/bunny_npm.obj");
  const std::string out = dir.file("three.png");
  const auto r = run_srcodec("render " + q(spot) + " " + q(bunny) + " " + q(spot) + " -o " + q(out) +
                             " --resolution 64 --view 7");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const StatusOr<std::string> bytes = read_file_bytes(out);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(png_size(*bytes), std::make_pair(int64_t{3 * 64 + 2 * 2}, int64_t{64}));

  const auto along = run_srcodec("render " + q(spot) + " -o " + q(dir.file("one.png")) +
                                 " --direction=-1,0.5,2e-1 --up 0,1,0");
  ASSERT_EQ(along.exit_code, 0) << along.err;
  EXPECT_EQ(png_size(*read_file_bytes(dir.file("one.png"))), std::make_pair(int64_t{512}, int64_t{512}));
}

TEST(RenderCli, BadInputFailsWithOneLineAndWritesNothing) {
  test::ScratchDir dir;
  const std::string spot = test::source_path("data/spot.obj");
  const std::string garbage = dir.write("garbage.obj", "not a mesh\n");
  const std::string out = dir.file("out.png");
  expect_one_line_error(run_srcodec("render " + q(spot) + " " + q(dir.file("missing.obj")) + " -o " + q(out)), 1,
                        "missing.obj: no such file");
  expect_one_line_error(run_srcodec("render " + q(garbage) + " -o " + q(out)), 1, "garbage.obj");
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(out) + " --view 16"), 2, "--view 16");
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(out) + " --direction 1,2"), 2, "--direction");
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(out) + " --direction 0,0,0"), 2, "not all 0");
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(out) + " --view 1 --direction 1,0,0"), 2,
                        "cannot be given together");
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(out) + " --direction 0,0,1 --up 0,0,-3"), 1,
                        "up direction");
  expect_one_line_error(run_srcodec("render -o " + q(out)), 2, "MESH is missing");
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(dir.file("out.jpg"))), 1, ".png");
  EXPECT_FALSE(read_file_bytes(out).ok()) << "a failed render left " << out;

  // Outputs that cannot be written: a missing folder, a folder, a file as a folder.
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(dir.file("no/out.png"))), 1, "does not exist");
  std::filesystem::create_directory(dir.file("folder.png"));
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(dir.file("folder.png"))), 1, "is a directory");
  ASSERT_EQ(run_srcodec("render " + q(spot) + " -o " + q(dir.file("x.png")) + " --resolution 16").exit_code, 0);
  expect_one_line_error(run_srcodec("render " + q(spot) + " -o " + q(dir.file("x.png/out.png"))), 1,
                        "does not exist");

  // A failure leaves what was at the output as it was.
  const std::string before = dir.write("kept.png", "earlier bytes");
  expect_one_line_error(run_srcodec("render " + q(garbage) + " -o " + q(before)), 1, "garbage.obj");
  EXPECT_EQ(*read_file_bytes(before), "earlier bytes");
}

}  // namespace
}  // namespace srcodec
