// Meshes a user may hand `srcodec encode` that are broken, tiny or odd
// (issue: untrusted input): each either encodes and decodes to the same
// surface, or fails with one line that names the file and what is wrong,
// and writes nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "format/file_io.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

using test::json_number;
using test::run_srcodec;
const auto q = test::shell_quote;

std::string obj_of(const TriangleMesh& mesh, const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  std::string out;
  char line[128];
  for (const auto& p : mesh.positions) {
    const Eigen::Vector3d x = p + offset;
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", x.x(), x.y(), x.z());
    out += line;
  }
  for (const auto& t : mesh.triangles) out += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  return out;
}

struct Outcome {
  int encode_exit = -1;
  std::string error;  // encode's stderr when it failed
  double hausdorff_over_diag = NAN, psnr = NAN;
};

// Encodes, decodes to the finest level and measures the result against the input.
Outcome round_trip(const test::ScratchDir& dir, const std::string& name, const std::string& contents) {
  const std::string in = dir.write(name, contents);
  const std::string srm = dir.file(name + ".srm"), out = dir.file(name + ".out.obj");
  Outcome o;
  auto e = run_srcodec("encode -q " + q(in) + " -o " + q(srm));
  o.encode_exit = e.exit_code;
  if (e.exit_code != 0) {
    o.error = e.err;
    EXPECT_FALSE(read_file_bytes(srm).ok()) << name << ": a failed encode left " << srm;
    return o;
  }
  auto d = run_srcodec("decode " + q(srm) + " -o " + q(out));
  EXPECT_EQ(d.exit_code, 0) << name << ": " << d.err;
  auto c = run_srcodec("compare --json --samples 20000 " + q(in) + " " + q(out));
  EXPECT_EQ(c.exit_code, 0) << name << ": " << c.err;
  o.hausdorff_over_diag = json_number(c.out, "hausdorff") / json_number(c.out, "diag");
  o.psnr = json_number(c.out, "psnr");
  return o;
}

void expect_one_line_error(const Outcome& o, const std::string& name, const std::string& what) {
  EXPECT_EQ(o.encode_exit, 1) << name;
  EXPECT_EQ(std::count(o.error.begin(), o.error.end(), '\n'), 1) << name << ":\n" << o.error;
  EXPECT_NE(o.error.find(name), std::string::npos) << o.error;
  EXPECT_NE(o.error.find(what), std::string::npos) << o.error;
}

TEST(BadMeshCli, BrokenFilesFailWithOneLineNamingTheProblem) {
  test::ScratchDir dir;
  expect_one_line_error(round_trip(dir, "empty.obj", ""), "empty.obj", "empty");
  expect_one_line_error(round_trip(dir, "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "points.obj", "no faces");
  expect_one_line_error(round_trip(dir, "nan.obj", "v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n"), "nan.obj",
                        "line 2");
  expect_one_line_error(round_trip(dir, "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n"), "range.obj",
                        "vertex index 7");
}

// Tiny inputs have fewer vertices than the smallest default base mesh: they
// become the base mesh and come back to within the base quantization.
TEST(BadMeshCli, TinyMeshesAreTheirOwnBaseMesh) {
  test::ScratchDir dir;
  const char* triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const char* two = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nv 6 5 5\nv 5 6 5\nf 1 2 3\nf 4 5 6\n";
  const std::string square = obj_of(test::flat_square(1));
  // Four triangles on one edge: cut into two manifold pieces.
  const char* fan = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\nf 1 2 3\nf 2 1 4\nf 1 2 5\nf 2 1 6\n";
  std::string duplicates;  // a tetrahedron whose 4 corners are each written 250000 times
  const TriangleMesh tet = test::tetrahedron();
  for (int i = 0; i < 1000000; ++i) {
    const auto& p = tet.positions[i % 4];
    duplicates += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  }
  for (const auto& t : tet.triangles) duplicates += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";

  for (const auto& [name, contents] : {std::pair<std::string, std::string>{"triangle.obj", triangle},
                                       {"two.obj", two},
                                       {"square.obj", square},
                                       {"fan.obj", fan},
                                       {"duplicates.obj", duplicates}}) {
    const Outcome o = round_trip(dir, name, contents);
    ASSERT_EQ(o.encode_exit, 0) << name << ": " << o.error;
    EXPECT_LT(o.hausdorff_over_diag, 1e-5) << name;
  }
}

// Far from the origin, float coordinates keep 7 digits: the same sphere
// centred at 1e7 must code as well as at the origin.
TEST(BadMeshCli, CoordinatesAround1e7CodeAsWellAsAtTheOrigin) {
  test::ScratchDir dir;
  const TriangleMesh sphere = test::icosphere(2, 3.0);  // 162 vertices
  const Outcome near = round_trip(dir, "near.obj", obj_of(sphere));
  const Outcome far = round_trip(dir, "far.obj", obj_of(sphere, Eigen::Vector3d(1e7, -2e7, 3e7)));
  ASSERT_EQ(near.encode_exit, 0) << near.error;
  ASSERT_EQ(far.encode_exit, 0) << far.error;
  EXPECT_GT(near.psnr, 45.0);
  EXPECT_NEAR(far.psnr, near.psnr, 1.0);
}

}  // namespace
}  // namespace srcodec
