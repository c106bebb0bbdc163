// `srcodec encode`, `decode` and `info` on .srm files, as a user meets them.
#include <gtest/gtest.h>
#include <srcodec/srcodec.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "format/file_io.h"
#include "format/mesh.h"
#include "format/mesh_files/mesh_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::json_number;
using test::run_srcodec;
const auto q = test::shell_quote;

TEST(CodecCli, EncodeAtAByteBudgetThenDecodeEveryLevelAndPrefix) {
  test::ScratchDir dir;
  const std::string srm = dir.file("spot.srm");
  auto e = run_srcodec("encode -q --json --levels 2 --bytes 1800 " + q(test::source_path("data/spot.obj")) + " -o " +
                       q(srm));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_LE(json_number(e.out, "bytes"), 1800);
  EXPECT_GT(json_number(e.out, "bytes"), 1700);
  EXPECT_GT(json_number(e.out, "psnr"), 40);
  ASSERT_TRUE(read_file_bytes(srm).ok());
  EXPECT_LE(read_file_bytes(srm)->size(), 1800u);

  auto info = run_srcodec("info --json " + q(srm));
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_NE(info.out.find("\"format\": \"srm\""), std::string::npos) << info.out;
  EXPECT_EQ(json_number(info.out, "input_vertices"), 2930);
  EXPECT_EQ(json_number(info.out, "base_vertices"), json_number(e.out, "base_vertices"));

  double previous_triangles = 0;
  for (int level = 0; level <= 2; ++level) {
    auto d = run_srcodec("decode --json --level " + std::to_string(level) + " " + q(srm) + " -o " +
                         q(dir.file("l" + std::to_string(level) + ".obj")));
    ASSERT_EQ(d.exit_code, 0) << d.err;
    EXPECT_EQ(json_number(d.out, "level"), level);
    EXPECT_EQ(json_number(d.out, "triangles"), level == 0 ? json_number(d.out, "triangles") : 4 * previous_triangles);
    previous_triangles = json_number(d.out, "triangles");
  }
  // On one thread: the same file as the default decode's.
  auto one = run_srcodec("decode --single-thread " + q(srm) + " -o " + q(dir.file("one.obj")));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_EQ(read_file_bytes(dir.file("one.obj")).value(), read_file_bytes(dir.file("l2.obj")).value());
  // A prefix decodes; one that ends inside the header says so and writes nothing.
  auto prefix = run_srcodec("decode --json --bytes 1200 " + q(srm) + " -o " + q(dir.file("p.obj")));
  EXPECT_EQ(prefix.exit_code, 0) << prefix.err;
  auto header = run_srcodec("decode --bytes 20 " + q(srm) + " -o " + q(dir.file("h.obj")));
  EXPECT_EQ(header.exit_code, 1);
  EXPECT_NE(header.err.find("inside its"), std::string::npos) << header.err;
  EXPECT_FALSE(read_file_bytes(dir.file("h.obj")).ok());
}

// With no rate option, encode keeps the knee of the rate-distortion curve
// (codec/rate_control.h) and says so; it says each stage as it ends.
TEST(CodecCli, EncodeWithNoRateKeepsTheKnee) {
  test::ScratchDir dir;
  const std::string srm = dir.file("spot.srm");
  auto e = run_srcodec("encode --json --levels 2 " + q(test::source_path("data/spot.obj")) + " -o " + q(srm));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_NE(e.out.find("\"rate\": \"the knee at 1 dB/bpv\""), std::string::npos) << e.out;
  EXPECT_NE(e.err.find("no rate option given"), std::string::npos) << e.err;
  EXPECT_NE(e.err.find(" measured: keeping "), std::string::npos) << e.err;
  // Every stage that can take long on a large input says when it is done,
  // in the order they run.
  size_t at = 0;
  for (const char* line : {"encode: read: ", "remesh: components: ", "remesh: oversampled ", "remesh: sites: ",
                           "remesh: base mesh: ", "remesh: refinement set up: ", "remesh: level 1: ",
                           "remesh: level 2: ", "remesh: fit: ", "remesh: slivers: ", "cuts estimated, "}) {
    const size_t found = e.err.find(line, at);
    EXPECT_NE(found, std::string::npos) << "no \"" << line << "\" after the lines before it:\n" << e.err;
    if (found != std::string::npos) at = found;
  }
  EXPECT_LT(json_number(e.out, "bytes"), json_number(e.out, "full_stream_bytes"));
  EXPECT_GT(json_number(e.out, "bytes"), json_number(e.out, "minimum_bytes"));
  EXPECT_EQ(static_cast<double>(read_file_bytes(srm)->size()), json_number(e.out, "bytes"));
}

TEST(CodecCli, BadRequestsSayWhatAndKeepWhatWasThere) {
  test::ScratchDir dir;
  const std::string in = q(test::source_path("data/spot.obj"));
  const std::string keep = dir.write("keep.srm", "precious");
  auto tiny = run_srcodec("encode -q --levels 1 --bytes 10 " + in + " -o " + q(keep));
  EXPECT_EQ(tiny.exit_code, 1);
  EXPECT_NE(tiny.err.find("header, base mesh and refinement flags"), std::string::npos) << tiny.err;
  EXPECT_EQ(read_file_bytes(keep).value(), "precious") << "a failed encode must leave the old file alone";
  auto folder = run_srcodec("encode -q " + in + " -o " + q(dir.file("no/such/dir/x.srm")));
  EXPECT_EQ(folder.exit_code, 1);
  EXPECT_NE(folder.err.find("does not exist"), std::string::npos) << folder.err;
  auto both = run_srcodec("encode -q --bytes 100 --psnr 50 " + in + " -o " + q(dir.file("x.srm")));
  EXPECT_NE(both.exit_code, 0);
  auto not_srm = run_srcodec("decode " + in + " -o " + q(dir.file("y.obj")));
  EXPECT_EQ(not_srm.exit_code, 1);
  EXPECT_NE(not_srm.err.find("not an .srm"), std::string::npos) << not_srm.err;
  auto golden = test::source_path("tests/data/golden_v1.srm");
  auto level = run_srcodec("decode --level 5 " + q(golden) + " -o " + q(dir.file("z.obj")));
  EXPECT_EQ(level.exit_code, 1);
  EXPECT_NE(level.err.find("has levels 0..2"), std::string::npos) << level.err;
  auto unreachable = run_srcodec("encode -q --levels 1 --psnr 150 " + in + " -o " + q(dir.file("u.srm")));
  EXPECT_EQ(unreachable.exit_code, 1);
  EXPECT_NE(unreachable.err.find("out of reach"), std::string::npos) << unreachable.err;
}

// `info` shows the creases of a version-3 file (tests/data/creases_v3.srm:
// 10 of its 30 base edges), and a file without them shows none.
TEST(CodecCli, InfoShowsTheCreases) {
  const std::string v3 = q(test::source_path("tests/data/creases_v3.srm"));
  auto text = run_srcodec("info " + v3);
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find(".srm version 3"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("creases: 10 base edges, 5 bytes"), std::string::npos) << text.out;
  auto json = run_srcodec("info --json " + v3);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_EQ(json_number(json.out, "crease_edges"), 10);
  EXPECT_EQ(json_number(json.out, "crease_bytes"), 5);
  auto plain = run_srcodec("info " + q(test::source_path("tests/data/golden_v2.srm")));
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(plain.out.find("creases"), std::string::npos) << plain.out;
  auto plain_json = run_srcodec("info --json " + q(test::source_path("tests/data/golden_v2.srm")));
  EXPECT_EQ(json_number(plain_json.out, "crease_edges"), 0);
}

// A cube, all creases, keeps its edges by default (--creases auto): the file
// records them and the decoded default-rate cube shows fewer visibly wrong
// pixels than the same encode with --creases off, whose edges ripple.
TEST(CodecCli, CreasesKeepACubesEdgesThroughTheCoding) {
  test::ScratchDir dir;
  const TriangleMesh cube = test::grid_cube(20);
  std::string obj;
  for (const auto& p : cube.positions)
    obj += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  for (const auto& t : cube.triangles)
    obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  const std::string in = q(dir.write("cube.obj", obj));
  double defects[2] = {0.0, 0.0};
  for (int features = 0; features < 2; ++features) {
    const std::string srm = q(dir.file("c.srm")), out = q(dir.file("c.obj"));
    auto e = run_srcodec("encode -q --levels 3 --base-vertices 40 " + std::string(features ? "" : "--creases off ") +
                         in + " -o " + srm);
    ASSERT_EQ(e.exit_code, 0) << e.err;
    auto info = run_srcodec("info --json " + srm);
    EXPECT_EQ(json_number(info.out, "crease_edges") > 0, features == 1) << info.out;
    ASSERT_EQ(run_srcodec("decode " + srm + " -o " + out).exit_code, 0);
    auto c = run_srcodec("compare --json " + in + " " + out);
    ASSERT_EQ(c.exit_code, 0) << c.err;
    defects[features] = json_number(c.out, "defect_share");
  }
  EXPECT_LT(defects[1], 0.5 * defects[0]) << "defect pixels with " << defects[1] << ", without " << defects[0];
  auto bad = run_srcodec("encode -q --creases sharp " + in + " -o " + q(dir.file("d.srm")));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--creases sharp: use auto, keep or off"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("d.srm")));
}

// An OBJ's vertices, normals (`vn`) and triangles' corners `v//vn`, counted from 0.
struct ObjWithNormals {
  std::vector<Eigen::Vector3d> positions, normals;
  std::vector<std::array<int, 6>> faces;  // v0 n0 v1 n1 v2 n2
};

ObjWithNormals read_obj_with_normals(const std::string& text) {
  ObjWithNormals out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::string tag;
    in >> tag;
    Eigen::Vector3d p;
    if (tag == "v" || tag == "vn") {
      in >> p.x() >> p.y() >> p.z();
      (tag == "v" ? out.positions : out.normals).push_back(p);
    } else if (tag == "f") {
      std::array<int, 6> f{};
      char slash;
      for (int k = 0; k < 3; ++k) in >> f[2 * k] >> slash >> slash >> f[2 * k + 1];
      for (int& i : f) --i;
      out.faces.push_back(f);
    }
  }
  return out;
}

// `decode` to OBJ of a file with creases (tests/data/cube_creases_v3.srm, a
// cube creased at its 12 edges, made by tools/make_golden.sh cube) writes
// normals split at them: every normal is a face normal of the cube, and so
// is each corner's triangle's, but for two slivers folded over at a corner.
// To the other formats, and for files without creases, it writes what
// write_mesh writes of the decoded mesh.
TEST(CodecCli, DecodeWritesNormalsSplitAtTheCreasesToObj) {
  test::ScratchDir dir;
  const std::string cube = test::source_path("tests/data/cube_creases_v3.srm");
  auto d = run_srcodec("decode --json " + q(cube) + " -o " + q(dir.file("cube.obj")));
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_NE(d.out.find("\"crease_normals\": true"), std::string::npos) << d.out;
  EXPECT_GT(json_number(d.out, "crease_edges"), 31) << d.out;  // the base's 31, split by the levels
  const ObjWithNormals obj = read_obj_with_normals(read_file_bytes(dir.file("cube.obj")).value());
  ASSERT_EQ(obj.positions.size(), json_number(d.out, "vertices"));
  ASSERT_EQ(obj.faces.size(), json_number(d.out, "triangles"));
  EXPECT_GT(obj.normals.size(), obj.positions.size());
  const double close = std::cos(0.5 * std::acos(-1.0) / 180);  // half a degree
  for (const Eigen::Vector3d& n : obj.normals) EXPECT_GT(n.cwiseAbs().maxCoeff(), close) << n.transpose();
  int off_face = 0;
  for (const auto& f : obj.faces) {
    const Eigen::Vector3d& a = obj.positions[f[0]];
    const Eigen::Vector3d face = (obj.positions[f[2]] - a).cross(obj.positions[f[4]] - a).normalized();
    for (int k = 0; k < 3; ++k) off_face += face.dot(obj.normals[f[2 * k + 1]]) < close;
  }
  EXPECT_LE(off_face, 6);
  // The OBJ's mesh is the decoded mesh; the PLY has no normals.
  const std::string bytes = read_file_bytes(cube).value();
  const StatusOr<Decoded> decoded = decode(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  ASSERT_TRUE(decoded.ok()) << decoded.status().message();
  const StatusOr<PolygonMesh> as_written = read_polygon_mesh(dir.file("cube.obj"));  // not cleaned
  ASSERT_TRUE(as_written.ok()) << as_written.status().message();
  ASSERT_EQ(3 * as_written->positions.size(), decoded->mesh.positions.size());
  // (As floats: a coordinate that is a float is written as the float's
  // shortest text, which the reader takes for the nearest double.)
  for (size_t v = 0; v < as_written->positions.size(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double coordinate = decoded->mesh.positions[3 * v + k];
      ASSERT_EQ(static_cast<float>(as_written->positions[v][k]), static_cast<float>(coordinate)) << v;
    }
  ASSERT_EQ(as_written->corners.size(), decoded->mesh.triangles.size());
  for (size_t c = 0; c < as_written->corners.size(); ++c)
    ASSERT_EQ(static_cast<uint32_t>(as_written->corners[c]), decoded->mesh.triangles[c]) << c;
  ASSERT_TRUE(write_mesh(dir.file("plain.ply"), decoded->mesh).ok());
  ASSERT_EQ(run_srcodec("decode " + q(cube) + " -o " + q(dir.file("cube.ply"))).exit_code, 0);
  EXPECT_EQ(read_file_bytes(dir.file("cube.ply")).value(), read_file_bytes(dir.file("plain.ply")).value());
  // Without creases: write_mesh's bytes, no normals.
  for (const char* name : {"spot_default.srm", "golden_v2.srm"}) {
    const std::string path = test::source_path(std::string("tests/data/") + name);
    auto plain = run_srcodec("decode --json " + q(path) + " -o " + q(dir.file("plain.obj")));
    ASSERT_EQ(plain.exit_code, 0) << plain.err;
    EXPECT_NE(plain.out.find("\"crease_normals\": false"), std::string::npos) << plain.out;
    const std::string file = read_file_bytes(path).value();
    const StatusOr<Decoded> mesh = decode(reinterpret_cast<const uint8_t*>(file.data()), file.size());
    ASSERT_TRUE(write_mesh(dir.file("library.obj"), mesh->mesh).ok());
    const std::string written = read_file_bytes(dir.file("plain.obj")).value();
    EXPECT_EQ(written, read_file_bytes(dir.file("library.obj")).value()) << name;
    EXPECT_EQ(written.find("vn"), std::string::npos) << name;
  }
}

// An encode stopped by the user (Ctrl-C, after a second) leaves no partial
// file behind: the old file stays as it was, and no temporary file is left.
// Should the encode finish first (a fast machine), the file is whole.
TEST(CodecCli, InterruptedEncodeLeavesNoPartialFile) {
  test::ScratchDir dir;
  const std::string out = dir.write("out.srm", "precious");
  auto run = test::run_binary("timeout", "-s INT 1 " + q(SRCODEC_BINARY) + " encode -q " +
                                             q(test::source_path("data/spot.obj")) + " -o " + q(out));
  if (run.exit_code == 0) {
    auto info = run_srcodec("info " + q(out));
    EXPECT_EQ(info.exit_code, 0) << info.err;
  } else {
    EXPECT_EQ(read_file_bytes(out).value(), "precious") << run.err;
  }
  size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(out).parent_path()))
    files += entry.path().filename() == "out.srm" ? 0 : 1;
  EXPECT_EQ(files, 0u) << "a temporary file was left";
}

}  // namespace
}  // namespace srcodec
