// The srcodec binary as a user meets it: exit codes, one-line errors, JSON.
#include <gtest/gtest.h>


#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::run_srcodec;

using test::json_number;
const auto q = test::shell_quote;

// The benchmark program with the switches for experiments (tools/bench/remesh_experiment.cpp).
test::CommandResult run_experiment(const std::string& args) {
  return test::run_binary(SRCODEC_EXPERIMENT_BINARY, args);
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

  // What a viewer sees: 12 bits leave small differences in shading, none turned over.
  EXPECT_GT(json_number(c.out, "mean_normal_degrees"), 0.0);
  EXPECT_LT(json_number(c.out, "mean_normal_degrees"), 5.0);
  EXPECT_LT(json_number(c.out, "defect_share"), 0.01);
  EXPECT_EQ(json_number(c.out, "turned_over_share"), 0.0);
  EXPECT_EQ(json_number(c.out, "views"), 16);

  auto self = run_srcodec("compare --json --samples 20000 " + q(sample) + " " + q(sample));
  ASSERT_EQ(self.exit_code, 0) << self.err;
  EXPECT_LT(json_number(self.out, "rms"), 1e-12 * 15.7572);  // rounding only
  EXPECT_EQ(json_number(self.out, "mean_normal_degrees"), 0.0);
  EXPECT_EQ(json_number(self.out, "defect_share"), 0.0);

  auto plain = run_srcodec("compare --no-visual --samples 20000 " + q(sample) + " " + q(sample));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.out.find("views"), std::string::npos) << plain.out;
}

TEST(Cli, RemeshSampleReportsEveryLevel) {
  test::ScratchDir dir;
  const std::string out = dir.file("bunny_sr.obj");
  auto r = run_srcodec("remesh --json --quiet --levels 2 --samples 20000 " + q(test::source_path("data/bunny_npm.obj")) +
                       " -o " + q(out) + " --write-levels " + q(dir.file("lv")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << "--quiet prints no progress: " << r.err;
  for (const char* level : {"\"level\": 0", "\"level\": 1", "\"level\": 2"})
    EXPECT_NE(r.out.find(level), std::string::npos) << r.out;
  EXPECT_EQ(json_number(r.out, "input_vertices"), 1839);
  EXPECT_GE(json_number(r.out, "oversample_steps"), 1);  // 1839 vertices are coarse for 2 levels over 100
  for (const std::string& f : {out, dir.file("lv_l0.obj"), dir.file("lv_l1.obj"), dir.file("lv_l2.obj")}) {
    auto bytes = read_file_bytes(f);
    ASSERT_TRUE(bytes.ok()) << f;
    EXPECT_GT(bytes->size(), 100u) << f;
  }
  // The finest level measured against the input: a finite, plausible PSNR.
  const double psnr = json_number(r.out.substr(r.out.rfind("\"level\": 2")), "psnr");
  EXPECT_GT(psnr, 40.0);
  EXPECT_LT(psnr, 120.0);
}

// Folded triangles are a defect the user should see without --json: the text
// report names them with the JSON's counts, and a clean remesh says nothing.
// Linear oversampling of the sample leaves a pleat on a coarser level at 4
// levels, and the refinement alone (no untangling) leaves tangles at 3; both
// checks say so when a remesher change makes that setting clean.
TEST(Cli, RemeshTextReportNamesLeftoverFolds) {
  test::ScratchDir dir;
  const std::string in = q(test::source_path("data/bunny_npm.obj"));
  const std::string args = " --quiet --levels 4 --scheme linear --samples 20000 " + in + " -o ";
  // By default the count is the untangling's, of the output.
  auto json = run_srcodec("remesh --json" + args + q(dir.file("a.obj")));
  ASSERT_EQ(json.exit_code, 0) << json.err;
  auto count = [&](const std::string& key) { return std::to_string(static_cast<size_t>(json_number(json.out, key))); };
  ASSERT_GT(json_number(json.out, "untangled_folded_by_nearest_input") +
                json_number(json.out, "untangled_coarser_folded_by_nearest_input") +
                json_number(json.out, "untangled_pleats") + json_number(json.out, "untangled_coarser_pleats"),
            0.0)
      << "this setting no longer folds: pick another for the test";
  auto text = run_srcodec("remesh" + args + q(dir.file("b.obj")));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::string line = "folds: " + count("untangled_folded_by_nearest_input") + " triangle(s) of level 4 and " +
                           count("untangled_coarser_folded_by_nearest_input") +
                           " of coarser levels face against the input (corners judged by its nearest vertices); " +
                           count("untangled_pleats") + " and " + count("untangled_coarser_pleats") + " edge(s) pleat";
  EXPECT_NE(text.out.find(line), std::string::npos) << text.out;
  // And where: the JSON lists the places (remesh/untangle.h, tangled_places),
  // the text the first of them, with its counts.
  const size_t places = json.out.find("\"tangled_places\": [{");
  ASSERT_NE(places, std::string::npos) << json.out;
  const std::string first = json.out.substr(places);
  auto place_count = [&](const std::string& key) {
    return std::to_string(static_cast<size_t>(json_number(first, key)));
  };
  const std::string where = "\n  at (";
  const std::string counts = ": " + place_count("folded") + " + " + place_count("coarser_folded") + " folded, " +
                             place_count("pleats") + " + " + place_count("coarser_pleats") + " pleats\n";
  const size_t at = text.out.find(where);
  ASSERT_NE(at, std::string::npos) << text.out;
  EXPECT_NE(text.out.find(counts, at), std::string::npos) << counts << "\n" << text.out;

  // Without the untangling, the refinement's own count (3 levels leave some).
  const std::string plain = " --no-untangle --quiet --levels 3 --scheme linear --samples 20000 " + in + " -o ";
  json = run_experiment("remesh --json" + plain + q(dir.file("c.obj")));
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const std::string last = json.out.substr(json.out.rfind("\"level\": 3"));
  const auto folded = static_cast<size_t>(json_number(last, "folded_triangles"));
  const auto coarse = static_cast<size_t>(json_number(last, "coarse_folded_triangles"));
  const auto pleats = static_cast<size_t>(json_number(last, "pleats"));
  ASSERT_GT(folded + coarse + pleats, 0u) << "this setting no longer folds: pick another for the test";
  text = run_experiment("remesh" + plain + q(dir.file("d.obj")));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const std::string refined = "folds: " + std::to_string(folded) + " triangle(s) of level 3 and " +
                              std::to_string(coarse) + " of coarser levels face against the input; " +
                              std::to_string(pleats) + " edge(s) pleat";
  EXPECT_NE(text.out.find(refined), std::string::npos) << text.out;

  auto clean = run_srcodec("remesh --quiet --levels 2 --samples 20000 " + in + " -o " + q(dir.file("e.obj")));
  ASSERT_EQ(clean.exit_code, 0) << clean.err;
  EXPECT_EQ(clean.out.find("folds:"), std::string::npos) << clean.out;
  EXPECT_EQ(clean.out.find("  at ("), std::string::npos) << clean.out;
}

// The unsplitting (remesh/unsplit_tangles.h) is off for remesh and encode
// alike, and neither has a switch for it; the experiments' program turns it
// on.
TEST(Cli, UnsplittingIsOffForRemeshAndEncode) {
  test::ScratchDir dir;
  const std::string in = q(test::source_path("data/bunny_npm.obj"));
  const std::string args = " --json --quiet --levels 2 --samples 20000 " + in + " -o ";
  auto on = [](const test::CommandResult& r) { return r.out.find("\"unsplit_tangles\": true") != std::string::npos; };
  auto off = [](const test::CommandResult& r) { return r.out.find("\"unsplit_tangles\": false") != std::string::npos; };
  auto r = run_srcodec("remesh" + args + q(dir.file("a.obj")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(off(r)) << r.out;
  EXPECT_EQ(json_number(r.out, "unsplit_passes"), 0.0);
  r = run_srcodec("encode" + args + q(dir.file("c.srm")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(off(r)) << r.out;
  EXPECT_EQ(json_number(r.out, "unsplit_splits"), 0.0);
  for (const char* command : {"remesh", "encode"})
    for (const char* flag : {"--unsplit-tangles", "--keep-tangled-splits"})
      EXPECT_NE(run_srcodec(std::string(command) + " " + flag + args + q(dir.file("e.out"))).exit_code, 0)
          << command << " " << flag;
  r = run_experiment("remesh --unsplit-tangles" + args + q(dir.file("f.obj")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(on(r)) << r.out;
}

// The switches for experiments are not the user's.
TEST(Cli, ExperimentSwitchesAreNotInTheUsersRemesh) {
  test::ScratchDir dir;
  const std::string in = q(test::source_path("data/bunny_npm.obj"));
  for (const char* flag : {"--tolerance 60", "--no-fit-surface", "--no-untangle", "--no-relax-slivers",
                           "--follow-detours"})
    EXPECT_NE(run_srcodec(std::string("remesh --quiet ") + flag + " " + in + " -o " + q(dir.file("x.obj"))).exit_code,
              0)
        << flag;
}

TEST(Cli, SubdivideLinearSplitsEveryTriangleInFour) {
  test::ScratchDir dir;
  const std::string in = q(test::source_path("data/bunny_npm.obj")), out = dir.file("lin.obj");
  auto r = run_srcodec("subdivide --scheme linear --steps 2 " + in + " -o " + q(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("1839 vertices, 3674 triangles -> "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(": 29394 vertices, 58784 triangles"), std::string::npos) << r.out;  // closed, genus 0
  // On the input's facets, up to the OBJ's printed digits (222 dB measured).
  auto same = run_srcodec("compare --json --samples 20000 " + in + " " + q(out));
  ASSERT_EQ(same.exit_code, 0) << same.err;
  EXPECT_GT(json_number(same.out, "psnr"), 180.0) << same.out;
}

TEST(Cli, RemeshBadRequestsSayWhatWouldWork) {
  test::ScratchDir dir;
  const std::string in = q(test::source_path("data/bunny_npm.obj")), out = dir.file("x.obj");
  auto big = run_srcodec("remesh --quiet --oversample 0 --base-vertices 5000 " + in + " -o " + q(out));
  EXPECT_EQ(big.exit_code, 1);
  EXPECT_NE(big.err.find("base vertices"), std::string::npos) << big.err;
  EXPECT_NE(big.err.find("ask for at most"), std::string::npos) << big.err;
  auto deep = run_srcodec("remesh --quiet --oversample 0 --levels 4 " + in + " -o " + q(out));
  EXPECT_EQ(deep.exit_code, 1);
  EXPECT_NE(deep.err.find("fewer levels"), std::string::npos) << deep.err;
  auto steps = run_srcodec("remesh --quiet --oversample 9 " + in + " -o " + q(out));
  EXPECT_NE(steps.exit_code, 0);
  for (const std::string command : {"remesh --quiet", "subdivide"}) {
    auto scheme = run_srcodec(command + " --scheme cubic " + in + " -o " + q(out));
    EXPECT_EQ(scheme.exit_code, 1) << command;
    EXPECT_NE(scheme.err.find("--scheme cubic: use butterfly, loop or linear"), std::string::npos) << scheme.err;
  }
  auto both = run_srcodec("remesh --quiet --uniform --threshold 3 " + in + " -o " + q(out));
  EXPECT_NE(both.exit_code, 0);
  for (const char* tolerance : {"0", "-5", "nan", "400", "x"}) {
    auto bad = run_experiment("remesh --quiet --tolerance " + std::string(tolerance) + " " + in + " -o " + q(out));
    EXPECT_NE(bad.exit_code, 0) << "--tolerance " << tolerance;
    EXPECT_NE(bad.err.find("--tolerance"), std::string::npos) << bad.err;
  }
  // NaN and infinities get past comparisons; every real-valued option refuses them.
  for (const std::string option : {"remesh --threshold", "encode --bpv", "encode --psnr", "encode --tangential-factor"})
    for (const char* value : {"nan", "inf", "-inf"}) {
      auto bad = run_srcodec(option + " " + value + " --quiet " + in + " -o " + q(dir.file("x.srm")));
      EXPECT_NE(bad.exit_code, 0) << option << " " << value;
      EXPECT_NE(bad.err.find("finite"), std::string::npos) << option << " " << value << ": " << bad.err;
    }
  EXPECT_FALSE(read_file_bytes(dir.file("x.srm")).ok());
  auto folder = run_srcodec("remesh --quiet " + in + " -o " + q(dir.file("no/such/folder/x.obj")));
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_NE(folder.err.find("does not exist"), std::string::npos) << folder.err;
  EXPECT_FALSE(read_file_bytes(out).ok()) << "a failed remesh must not leave an output file";
}

}  // namespace
}  // namespace srcodec
