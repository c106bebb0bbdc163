// The side-by-side pictures (tools/measure/shaded_render.h) on cases whose
// answers are known: how much of a panel a sphere covers, triangles turned
// over, identical meshes, panels that share one frame, which way is up, and
// the PNG read back.
#include "tools/measure/shaded_render.h"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <string>
#include <vector>

#include "tests/test_util.h"
#include "tools/measure/ray_cast.h"

namespace srcodec {
namespace {

constexpr double kPi = 3.14159265358979323846;

GreyImage rendered(const std::vector<TriangleMesh>& meshes, const ShadedRenderOptions& o) {
  const StatusOr<GreyImage> image = render_side_by_side(meshes, o);
  EXPECT_TRUE(image.ok()) << image.status().message();
  return image.ok() ? *image : GreyImage{};
}

ShadedRenderOptions at(const Eigen::Vector3d& direction, int resolution = 128) {
  ShadedRenderOptions o;
  o.direction = direction;
  o.resolution = resolution;
  return o;
}

// Panel k's pixels, row by row from the top.
std::vector<uint8_t> panel(const GreyImage& image, int k) {
  std::vector<uint8_t> out;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.height; ++x) out.push_back(image.at(panel_left(k, image.height) + x, y));
  return out;
}

size_t covered(const std::vector<uint8_t>& pixels) {
  size_t n = 0;
  for (uint8_t p : pixels) n += p != kBackgroundGrey;
  return n;
}

TEST(ShadedRender, ASphereCoversPiOverTwelveOfEveryView) {
  // The frame is the bounding box's half diagonal, r sqrt(3): the sphere's
  // disc covers pi r^2 of (2 r sqrt(3))^2.
  const TriangleMesh sphere = test::icosphere(4, 2.0);
  const int res = 128;
  for (const Eigen::Vector3d& d : view_directions(16)) {
    const GreyImage image = rendered({sphere}, at(d, res));
    ASSERT_EQ(image.width, res);
    ASSERT_EQ(image.height, res);
    EXPECT_NEAR(covered(image.pixels) / double(res * res), kPi / 12, 0.01 * kPi / 12) << d.transpose();
  }
}

TEST(ShadedRender, IdenticalMeshesGiveIdenticalPanels) {
  const TriangleMesh sphere = test::icosphere(3, 1.0);
  const GreyImage image = rendered({sphere, sphere, sphere}, at(view_directions(16)[5]));
  EXPECT_EQ(image.width, 3 * 128 + 2 * kPanelGap);
  EXPECT_EQ(panel(image, 0), panel(image, 1));
  EXPECT_EQ(panel(image, 0), panel(image, 2));
}

TEST(ShadedRender, TurnedOverTrianglesShowDark) {
  const TriangleMesh sphere = test::icosphere(3, 1.0);
  TriangleMesh flipped = sphere;
  for (size_t f = 3; f < flipped.triangles.size(); f += 7) std::swap(flipped.triangles[f][1], flipped.triangles[f][2]);
  const GreyImage image = rendered({sphere, flipped}, at(view_directions(16)[2], 256));
  const std::vector<uint8_t> a = panel(image, 0), b = panel(image, 1);
  size_t darker = 0, lighter = 0, back_faces_in_a = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    darker += b[i] < a[i];
    lighter += b[i] > a[i];
    back_faces_in_a += a[i] == kBackFaceGrey;
    if (b[i] != a[i]) {
      EXPECT_EQ(b[i], kBackFaceGrey);
    }
  }
  EXPECT_EQ(lighter, 0u);
  EXPECT_EQ(back_faces_in_a, 0u);  // a closed sphere seen from outside shows only front faces
  // A scattered seventh of the triangles covers about a seventh of the disc
  // (measured 0.1435; one view, so wider than the visual measure's 2%).
  EXPECT_NEAR(darker / double(covered(a)), 1.0 / 7, 0.1 / 7);
}

// The panels share the first mesh's frame: a copy at half the size covers
// a quarter of the pixels, and a copy moved up shows higher up.
TEST(ShadedRender, EveryPanelIsInTheFirstMeshsFrame) {
  const TriangleMesh sphere = test::icosphere(4, 1.0);
  TriangleMesh half = sphere, raised = sphere, right = sphere;
  for (auto& p : half.positions) p *= 0.5;
  for (auto& p : raised.positions) p.z() += 0.5;
  // Seen from -y with z up, the picture's right is +x.
  for (auto& p : right.positions) p.x() += 0.5;
  const int res = 256;
  const GreyImage image = rendered({sphere, half, raised, right}, at(-Eigen::Vector3d::UnitY(), res));
  const std::vector<uint8_t> whole = panel(image, 0);
  EXPECT_NEAR(covered(panel(image, 1)) / double(covered(whole)), 0.25, 0.01);
  const auto centroid = [&](const std::vector<uint8_t>& pixels) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (int i = 0; i < res * res; ++i)
      if (pixels[i] != kBackgroundGrey) sum += Eigen::Vector2d(i % res, i / res);
    return Eigen::Vector2d(sum / double(covered(pixels)));
  };
  // 0.5 is 0.5 / sqrt(3) of the frame's half width, res / 2 pixels.
  const double shift = 0.5 / std::sqrt(3.0) * res / 2;
  const Eigen::Vector2d c = centroid(whole), up = centroid(panel(image, 2)), r = centroid(panel(image, 3));
  EXPECT_NEAR(up.y() - c.y(), -shift, 0.5);  // rows count downwards
  EXPECT_NEAR(up.x() - c.x(), 0.0, 0.5);
  EXPECT_NEAR(r.x() - c.x(), shift, 0.5);
  EXPECT_NEAR(r.y() - c.y(), 0.0, 0.5);
}

TEST(ShadedRender, UpChoosesWhatShowsUpwards) {
  TriangleMesh raised = test::icosphere(3, 1.0);
  const TriangleMesh sphere = raised;
  for (auto& p : raised.positions) p.y() += 0.5;
  ShadedRenderOptions o = at(Eigen::Vector3d::UnitZ(), 64);
  o.up = Eigen::Vector3d::UnitY();
  const GreyImage image = rendered({sphere, raised}, o);
  // Raised along y, which shows upwards: the top rows gain pixels.
  const std::vector<uint8_t> a = panel(image, 0), b = panel(image, 1);
  EXPECT_GT(covered({b.begin(), b.begin() + 64 * 16}), covered({a.begin(), a.begin() + 64 * 16}));
}

TEST(ShadedRender, RefusesBadOptionsAndBadMeshes) {
  const TriangleMesh sphere = test::icosphere(2, 1.0);
  EXPECT_EQ(render_side_by_side({}, {}).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(render_side_by_side({sphere}, at(Eigen::Vector3d::Zero())).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(render_side_by_side({sphere}, at(Eigen::Vector3d(NAN, 0, 1))).status().code(),
            StatusCode::kInvalidArgument);
  EXPECT_EQ(render_side_by_side({sphere}, at(Eigen::Vector3d::UnitX(), 8)).status().code(),
            StatusCode::kInvalidArgument);
  ShadedRenderOptions along = at(Eigen::Vector3d::UnitX());
  along.up = Eigen::Vector3d(-2, 0, 0);
  EXPECT_EQ(render_side_by_side({sphere}, along).status().code(), StatusCode::kInvalidArgument);
  TriangleMesh flat = sphere;
  for (auto& p : flat.positions) p = Eigen::Vector3d(p.x(), 0, 0);  // no area
  const StatusOr<GreyImage> bad = render_side_by_side({sphere, flat}, at(Eigen::Vector3d::UnitX()), {"a.obj", "b.obj"});
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidMesh);
  EXPECT_NE(bad.status().message().find("b.obj"), std::string::npos) << bad.status().message();
}

TEST(GreyPng, ReadsBackAsWritten) {
  GreyImage image(37, 5, 0);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<uint8_t>(i * 7);
  const StatusOr<std::string> bytes = grey_png_bytes(image);
  ASSERT_TRUE(bytes.ok()) << bytes.status().message();
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_memory(&png, bytes->data(), bytes->size())) << png.message;
  EXPECT_EQ(png.width, 37u);
  EXPECT_EQ(png.height, 5u);
  png.format = PNG_FORMAT_GRAY;
  std::vector<uint8_t> back(PNG_IMAGE_SIZE(png));
  ASSERT_TRUE(png_image_finish_read(&png, nullptr, back.data(), 0, nullptr)) << png.message;
  EXPECT_EQ(back, image.pixels);
  EXPECT_FALSE(grey_png_bytes(GreyImage{}).ok());
}

}  // namespace
}  // namespace srcodec
