// `srcodec rd` end to end on the bundled sample (data/spot.obj, 2 levels to
// keep it fast): the CSV's columns and rows, the summary, the plot or its
// warning, reproducibility, and agreement with `encode --bytes` and `draco`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>

#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::run_srcodec;

std::string q(const std::string& s) { return "'" + s + "'"; }

using CsvRow = std::map<std::string, std::string>;

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  std::string cell;
  while (std::getline(in, cell, ',')) out.push_back(cell);
  return out;
}

// The header's names, and each row keyed by them.
std::vector<CsvRow> read_csv(const std::string& path, std::vector<std::string>* header) {
  auto text = read_file_bytes(path);
  EXPECT_TRUE(text.ok()) << text.status().message();
  std::stringstream in(text.ok() ? text.value() : "");
  std::string line;
  std::getline(in, line);
  *header = split(line);
  std::vector<CsvRow> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line);
    EXPECT_EQ(cells.size(), header->size()) << line;
    CsvRow row;
    for (size_t i = 0; i < cells.size() && i < header->size(); ++i) row[(*header)[i]] = cells[i];
    rows.push_back(row);
  }
  return rows;
}

double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9.eE+-]+)"))) return std::nan("");
  return std::stod(m[1]);
}

// 2 levels and a quarter of the default samples: each run takes seconds.
const std::string kSpotArgs = " --levels 2 --samples 50000 ";
constexpr double kSpotVertices = 2930;

class RdCli : public ::testing::Test {
 protected:
  // One run shared by the tests that only read its output.
  static void SetUpTestSuite() {
    dir_ = new test::ScratchDir();
    first_ = new test::CommandResult(run_srcodec("rd " + q(test::source_path("data/spot.obj")) + kSpotArgs + "-o " +
                                                 q(dir_->file("new/folder"))));
  }
  static void TearDownTestSuite() {
    delete first_;
    delete dir_;
  }
  static std::string out(const std::string& name) { return dir_->file("new/folder/" + name); }
  static test::ScratchDir* dir_;
  static test::CommandResult* first_;
};
test::ScratchDir* RdCli::dir_ = nullptr;
test::CommandResult* RdCli::first_ = nullptr;

TEST_F(RdCli, WritesTheCsvWithItsColumnsAndOneRowPerPoint) {
  ASSERT_EQ(first_->exit_code, 0) << first_->err;
  std::vector<std::string> header;
  const std::vector<CsvRow> rows = read_csv(out("rd.csv"), &header);
  EXPECT_EQ(header, (std::vector<std::string>{"codec", "setting", "bytes", "bpv", "psnr", "rms", "hausdorff",
                                              "encode_ms", "decode_ms", "normal_deg", "defect_share", "depth_psnr",
                                              "turned_over_share"}));
  int srcodec = 0, draco = 0;
  double previous_bytes = 0;
  for (const CsvRow& r : rows) {
    const double bytes = std::stod(r.at("bytes")), bpv = std::stod(r.at("bpv")), psnr = std::stod(r.at("psnr"));
    EXPECT_NEAR(bpv, 8 * bytes / kSpotVertices, 1e-5) << "bpv is per original input vertex";
    EXPECT_TRUE(std::isfinite(psnr) && psnr > 20) << r.at("setting");
    EXPECT_GT(std::stod(r.at("rms")), 0);
    EXPECT_GE(std::stod(r.at("hausdorff")), std::stod(r.at("rms")));
    EXPECT_GT(std::stod(r.at("encode_ms")), 0);
    EXPECT_GT(std::stod(r.at("decode_ms")), 0);
    // The visual measure: every figure present and in its range.
    const double angle = std::stod(r.at("normal_deg")), defects = std::stod(r.at("defect_share"));
    const double turned = std::stod(r.at("turned_over_share"));
    EXPECT_TRUE(angle > 0 && angle < 90) << r.at("setting") << " " << angle;
    EXPECT_TRUE(defects >= 0 && defects < 0.5) << r.at("setting") << " " << defects;
    EXPECT_TRUE(turned >= 0 && turned < 0.05) << r.at("setting") << " " << turned;
    EXPECT_GT(std::stod(r.at("depth_psnr")), 20) << r.at("setting");
    if (r.at("codec") == "srcodec") {
      ++srcodec;
      EXPECT_EQ(r.at("setting").rfind("bytes=", 0), 0u) << r.at("setting");
      EXPECT_LE(bytes, std::stod(r.at("setting").substr(6))) << "a file fits its budget";
      EXPECT_GT(bytes, previous_bytes) << "log-spaced, increasing";
      previous_bytes = bytes;
      EXPECT_EQ(r.at("encode_ms"), rows.front().at("encode_ms")) << "one remesh and encode for every point";
    } else {
      ASSERT_EQ(r.at("codec"), "draco");
      EXPECT_EQ(r.at("setting"), "qp=" + std::to_string(6 + draco));
      ++draco;
    }
  }
  EXPECT_EQ(srcodec, 10) << "--points defaults to 10";
  EXPECT_EQ(draco, 11) << "quantization bits 6..16";
  // The last srcodec point is the whole stream: the best PSNR of the sweep,
  // and what looks most like the input.
  EXPECT_GT(std::stod(rows[9].at("psnr")), std::stod(rows[0].at("psnr")) + 5.0);
  EXPECT_LT(std::stod(rows[9].at("normal_deg")), std::stod(rows[0].at("normal_deg")));
  EXPECT_LT(std::stod(rows[9].at("defect_share")), std::stod(rows[0].at("defect_share")));
  EXPECT_LT(std::stod(rows[20].at("normal_deg")), std::stod(rows[10].at("normal_deg")));  // Draco 16 bits against 6
}

TEST_F(RdCli, PrintsTheSummaryAndDrawsThePlot) {
  ASSERT_EQ(first_->exit_code, 0) << first_->err;
  for (const char* line : {"BD-rate srcodec vs draco:", "bytes srcodec/draco: 50 dB", "crossover", "seen at 70 dB",
                           "time srcodec/draco:"})
    EXPECT_NE(first_->out.find(line), std::string::npos) << line << " in\n" << first_->out;
  EXPECT_NE(first_->err.find("rd: srcodec bytes="), std::string::npos) << "progress on stderr";
  EXPECT_NE(first_->err.find("rd: draco qp=16"), std::string::npos);
  if (first_->err.find("warning: no plot") == std::string::npos) {
    EXPECT_TRUE(std::filesystem::file_size(out("rd.png")) > 1000);
  } else {
    ADD_FAILURE() << "no plot (is python3-matplotlib installed?): " << first_->err;
  }
  EXPECT_TRUE(std::filesystem::exists(out("summary.json")));
}

// The rows are the files `encode --bytes N` writes and the streams `draco --qp N` writes.
TEST_F(RdCli, RowsAgreeWithEncodeAndDraco) {
  ASSERT_EQ(first_->exit_code, 0) << first_->err;
  std::vector<std::string> header;
  const std::vector<CsvRow> rows = read_csv(out("rd.csv"), &header);
  ASSERT_GE(rows.size(), 21u);
  const CsvRow& middle = rows[4];
  const std::string mesh = q(test::source_path("data/spot.obj"));
  auto encoded = run_srcodec("encode " + mesh + kSpotArgs + "--json -q --" + middle.at("setting").substr(0, 5) + " " +
                             middle.at("setting").substr(6) + " -o " + q(dir_->file("middle.srm")));
  ASSERT_EQ(encoded.exit_code, 0) << encoded.err;
  EXPECT_EQ(json_number(encoded.out, "bytes"), std::stod(middle.at("bytes")));
  EXPECT_NEAR(json_number(encoded.out, "psnr"), std::stod(middle.at("psnr")), 1e-3);
  auto draco = run_srcodec("draco --qp 11 --json " + mesh);
  ASSERT_EQ(draco.exit_code, 0) << draco.err;
  EXPECT_EQ(rows[10 + 5].at("setting"), "qp=11");
  EXPECT_EQ(json_number(draco.out, "bytes"), std::stod(rows[10 + 5].at("bytes")));
}

// A second run: same bytes and distances; the JSON summary; a plot script
// that fails is one warning line, and the CSV and summary are still written.
TEST_F(RdCli, ReproducibleAndAFailingPlotIsAWarning) {
  ASSERT_EQ(first_->exit_code, 0) << first_->err;
  const std::string failing = dir_->write("fail.py", "import sys\nsys.exit('no matplotlib here')\n");
  ASSERT_EQ(setenv("SRCODEC_PLOT_SCRIPT", failing.c_str(), 1), 0);
  auto second = run_srcodec("rd " + q(test::source_path("data/spot.obj")) + kSpotArgs + "--json -q -o " +
                            q(dir_->file("second")));
  unsetenv("SRCODEC_PLOT_SCRIPT");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_NE(second.err.find("rd: warning: no plot:"), std::string::npos) << second.err;
  EXPECT_NE(second.err.find("no matplotlib here"), std::string::npos) << second.err;
  EXPECT_EQ(std::count(second.err.begin(), second.err.end(), '\n'), 1) << "-q: the warning only\n" << second.err;
  EXPECT_FALSE(std::filesystem::exists(dir_->file("second/rd.png")));
  EXPECT_EQ(second.out.front(), '{');
  EXPECT_EQ(std::count(second.out.begin(), second.out.end(), '\n'), 1) << second.out;
  EXPECT_NE(second.out.find("\"bd_rate\": "), std::string::npos);
  EXPECT_NE(second.out.find("\"seen_at\": "), std::string::npos);
  EXPECT_EQ(json_number(second.out, "input_vertices"), kSpotVertices);

  std::vector<std::string> h1, h2;
  const std::vector<CsvRow> a = read_csv(out("rd.csv"), &h1), b = read_csv(dir_->file("second/rd.csv"), &h2);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i)
    for (const char* column : {"codec", "setting", "bytes", "psnr", "rms", "hausdorff"})
      EXPECT_EQ(a[i].at(column), b[i].at(column)) << "row " << i << " " << column;
}

// --cut prefix: the rows are the whole stream's first N bytes, N exactly.
TEST(RdCliArguments, PrefixCutsAreExactPrefixes) {
  test::ScratchDir dir;
  auto r = run_srcodec("rd " + q(test::source_path("data/spot.obj")) +
                       " --levels 1 --points 3 --samples 5000 --cut prefix --no-plot --no-visual -q -o " +
                       q(dir.file("p")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("p/rd.png")));
  std::vector<std::string> header;
  const std::vector<CsvRow> rows = read_csv(dir.file("p/rd.csv"), &header);
  ASSERT_EQ(rows.size(), 3u + 11u);
  for (size_t i = 0; i < 3; ++i) EXPECT_EQ(rows[i].at("setting"), "prefix=" + rows[i].at("bytes"));
  for (const CsvRow& row : rows)  // --no-visual
    for (const char* column : {"normal_deg", "defect_share", "depth_psnr", "turned_over_share"})
      EXPECT_EQ(row.at(column), "nan") << column;
}

TEST(RdCliArguments, BadOptionsAndInputsFailWithOneLine) {
  test::ScratchDir dir;
  const std::string mesh = q(test::source_path("data/spot.obj"));
  for (const std::string& args : {"rd " + mesh + " -o " + q(dir.file("a")) + " --points 1",
                                  "rd " + mesh + " -o " + q(dir.file("a")) + " --cut middle",
                                  "rd " + mesh + " -o " + q(dir.file("a")) + " --scheme cubic",
                                  "rd " + q(dir.file("missing.obj")) + " -o " + q(dir.file("a")),
                                  "rd " + mesh + " -o " + q(dir.write("file", "x") + "/sub")}) {
    auto r = run_srcodec(args);
    EXPECT_NE(r.exit_code, 0) << args;
    EXPECT_FALSE(r.err.empty()) << args;
    EXPECT_FALSE(std::filesystem::exists(dir.file("a/rd.csv"))) << args;
  }
}

}  // namespace
}  // namespace srcodec
