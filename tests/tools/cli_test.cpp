// The srcodec binary as a user meets it: exit codes, one-line errors, JSON.
#include <gtest/gtest.h>

#include <regex>

#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::run_srcodec;

std::string q(const std::string& s) { return "'" + s + "'"; }

// A number field of a flat JSON line, NaN if absent.
double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9.eE+-]+)"))) return std::nan("");
  return std::stod(m[1]);
}

TEST(Cli, InfoJsonOnSample) {
  auto r = run_srcodec("info --json " + q(test::source_path("data/spot.obj")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(json_number(r.out, "vertices"), 2930);
  EXPECT_EQ(json_number(r.out, "faces"), 5856);
  EXPECT_EQ(json_number(r.out, "genus"), 0);
  EXPECT_EQ(json_number(r.out, "components"), 1);
  EXPECT_NE(r.out.find("\"cleaned\": {"), std::string::npos);
}

TEST(Cli, InfoOnCorpusAsTheIssueAsks) {
  if (!test::have_corpus()) GTEST_SKIP() << "corpus not present";
  auto ogre = run_srcodec("info --json " + q(test::corpus_path("ogre.obj")));
  ASSERT_EQ(ogre.exit_code, 0) << ogre.err;
  EXPECT_EQ(json_number(ogre.out, "components"), 44);
  EXPECT_EQ(json_number(ogre.out, "nonmanifold_vertices"), 3);
  auto lion = run_srcodec("info --json " + q(test::corpus_path("lionstatue.obj")));
  ASSERT_EQ(lion.exit_code, 0) << lion.err;
  EXPECT_EQ(json_number(lion.out, "genus"), 3);
  EXPECT_EQ(json_number(lion.out, "boundary_loops"), 1);
  auto beast = run_srcodec("info " + q(test::corpus_path("beast.obj")));
  ASSERT_EQ(beast.exit_code, 0) << beast.err;
  EXPECT_NE(beast.out.find("closed manifold"), std::string::npos) << beast.out;
}

TEST(Cli, BadInputGivesOneLineAndNonZeroExit) {
  test::ScratchDir dir;
  const std::vector<std::string> files = {
      dir.file("missing.obj"),
      dir.write("empty.obj", ""),
      dir.write("garbage.stl", std::string("\0\1\2\3\xff garbage", 13)),
      dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -7\n"),
      dir.write("nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"),
      dir.write("points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n"),
      dir.write("mesh.txt", "v 0 0 0\n"),
  };
  for (const auto& f : files) {
    for (const std::string& command : {"info " + q(f), "compare " + q(f) + " " + q(f), "draco --qp 11 " + q(f)}) {
      auto r = run_srcodec(command);
      EXPECT_EQ(r.exit_code, 1) << command << "\n" << r.err;
      EXPECT_NE(r.err.find(f), std::string::npos) << command << ": " << r.err;
      EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << command << ": " << r.err;
    }
  }
}

TEST(Cli, UsageErrorsExitNonZero) {
  EXPECT_NE(run_srcodec("").exit_code, 0);
  EXPECT_NE(run_srcodec("frobnicate").exit_code, 0);
  EXPECT_NE(run_srcodec("draco " + q(test::source_path("data/spot.obj"))).exit_code, 0);  // --qp missing
  EXPECT_NE(run_srcodec("draco --qp 99 " + q(test::source_path("data/spot.obj"))).exit_code, 0);
}

TEST(Cli, DracoThenCompareOnSample) {
  test::ScratchDir dir;
  const std::string sample = test::source_path("data/bunny_npm.obj");
  auto d = run_srcodec("draco --json --qp 12 " + q(sample) + " -o " + q(dir.file("b.drc")) + " --decoded " +
                       q(dir.file("b.obj")));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  const double bytes = json_number(d.out, "bytes");
  EXPECT_GT(bytes, 500);
  EXPECT_NEAR(json_number(d.out, "bpv"), 8 * bytes / 1839, 1e-6);
  auto drc = read_file_bytes(dir.file("b.drc"));
  ASSERT_TRUE(drc.ok());
  EXPECT_EQ(static_cast<double>(drc->size()), bytes);

  auto c = run_srcodec("compare --json --samples 20000 " + q(sample) + " " + q(dir.file("b.obj")));
  ASSERT_EQ(c.exit_code, 0) << c.err;
  const double psnr = json_number(c.out, "psnr");
  // 12-bit quantization: error about a cell/sqrt(12) per axis; PSNR near 6.02*12 + 10.
  EXPECT_GT(psnr, 70);
  EXPECT_LT(psnr, 95);
  EXPECT_NEAR(json_number(c.out, "diag"), 15.7572, 1e-3);

  auto self = run_srcodec("compare --json --samples 20000 " + q(sample) + " " + q(sample));
  ASSERT_EQ(self.exit_code, 0) << self.err;
  EXPECT_LT(json_number(self.out, "rms"), 1e-12 * 15.7572);  // rounding only
}

}  // namespace
}  // namespace srcodec
