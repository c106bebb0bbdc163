#include "tools/measure/visual_difference.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "remesh/folds.h"
#include "remesh/geometry.h"
#include "remesh/surface_distance.h"
#include "tools/measure/surface_distance.h"

namespace srcodec {
namespace {

constexpr double kPi = 3.14159265358979323846;
// In the frame's units (the reference's bounding radius): a depth difference
// over this is a different surface seen, not the same one moved.
constexpr double kDepthJump = 0.1;
// The farthest from the centre rays start, in the same units.
constexpr double kFarthestStart = 4.0;

// The frame every render is made in: the reference's bounding-box centre
// and half diagonal map to the origin and 1, so that Embree's single
// precision is spent on the shape and not on its offset.
struct Frame {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;
  Eigen::Vector3d to_unit(const Eigen::Vector3d& p) const { return (p - center) / radius; }
};

Frame bounding_frame(const MeasuredSurface& surface) {
  const TriangleMesh& mesh = *surface.mesh;
  Eigen::AlignedBox3d box;
  for (uint32_t f : surface.faces)
    for (int32_t v : mesh.triangles[f]) box.extend(mesh.positions[v]);
  Frame frame;
  frame.center = box.center();
  frame.radius = 0.5 * box.diagonal().norm();
  if (!(frame.radius > 0.0)) frame.radius = 1.0;  // cannot happen with positive area; kept finite anyway
  return frame;
}

// An orthographic view looking along -direction, the image spanned by u, v.
struct View {
  Eigen::Vector3d direction, u, v;
};

std::vector<View> views_from(const std::vector<Eigen::Vector3d>& directions) {
  std::vector<View> views;
  for (const Eigen::Vector3d& d : directions) {
    View view;
    view.direction = d;
    const Eigen::Vector3d helper = std::abs(d.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
    view.u = helper.cross(d).normalized();
    view.v = d.cross(view.u);
    views.push_back(view);
  }
  return views;
}

struct EmbreeDevice {
  RTCDevice device = nullptr;
  EmbreeDevice() : device(rtcNewDevice(nullptr)) {}
  ~EmbreeDevice() {
    if (device) rtcReleaseDevice(device);
  }
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;
};

Status embree_error(RTCDevice device, const std::string& what) {
  return internal_error("visual measure: Embree failed to " + what + " (error " +
                        std::to_string(static_cast<int>(rtcGetDeviceError(device))) + ")");
}

// One mesh's triangles of positive area in an Embree scene, in the frame.
class Scene {
 public:
  static StatusOr<std::unique_ptr<Scene>> build(RTCDevice device, const MeasuredSurface& surface, const Frame& frame) {
    std::unique_ptr<Scene> s(new Scene(surface));
    s->scene_ = rtcNewScene(device);
    if (!s->scene_) return embree_error(device, "create a scene");
    rtcSetSceneFlags(s->scene_, RTC_SCENE_FLAG_ROBUST);  // no cracks between neighbouring triangles
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (!geometry) return embree_error(device, "create a triangle geometry");
    const TriangleMesh& mesh = *surface.mesh;
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), surface.faces.size()));
    if (!vertices || !indices) {
      rtcReleaseGeometry(geometry);
      return embree_error(device, "allocate " + std::to_string(surface.faces.size()) + " triangles");
    }
    std::fill(vertices, vertices + 3 * mesh.positions.size(), 0.0f);  // unused vertices may be anything
    for (size_t i = 0; i < surface.faces.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const int32_t v = mesh.triangles[surface.faces[i]][c];
        indices[3 * i + c] = static_cast<unsigned>(v);
        const Eigen::Vector3d p = frame.to_unit(mesh.positions[v]);
        for (int k = 0; k < 3; ++k) vertices[3 * static_cast<size_t>(v) + k] = static_cast<float>(p[k]);
        s->extent_ = std::max(s->extent_, p.norm());
      }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(s->scene_, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(s->scene_);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) return embree_error(device, "build the scene");
    return s;
  }
  ~Scene() {
    if (scene_) rtcReleaseScene(scene_);
  }

  // The largest distance of a vertex from the frame's centre (1 for the
  // reference; a test mesh may reach farther).
  double extent() const { return extent_; }

  struct Hit {
    bool hit = false;
    double t = 0;       // along the ray
    uint32_t face = 0;  // index into mesh.triangles
  };
  Hit cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit ray{};
    ray.ray.org_x = static_cast<float>(origin.x());
    ray.ray.org_y = static_cast<float>(origin.y());
    ray.ray.org_z = static_cast<float>(origin.z());
    ray.ray.dir_x = static_cast<float>(direction.x());
    ray.ray.dir_y = static_cast<float>(direction.y());
    ray.ray.dir_z = static_cast<float>(direction.z());
    ray.ray.tnear = 0.0f;
    ray.ray.tfar = std::numeric_limits<float>::infinity();
    ray.ray.mask = ~0u;
    ray.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    ray.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &ray);
    Hit hit;
    if (ray.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
    hit.hit = true;
    hit.t = ray.ray.tfar;
    hit.face = surface_.faces[ray.hit.primID];
    return hit;
  }

  // The unit normal of face f (of positive area), in the faces' orientation.
  Eigen::Vector3d normal(uint32_t f) const {
    return triangle_normal(surface_.mesh->positions, surface_.mesh->triangles[f]).normalized();
  }

 private:
  explicit Scene(const MeasuredSurface& surface) : surface_(surface) {}
  const MeasuredSurface& surface_;
  RTCScene scene_ = nullptr;
  double extent_ = 0.0;
};

// What one pixel of a render shows: the depth (along the view, from the
// plane through the frame's centre) and the normal there, or nothing.
struct Pixel {
  float depth = std::numeric_limits<float>::quiet_NaN();  // NaN: the ray misses
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();
  bool covered() const { return !std::isnan(depth); }
};

// Every pixel of every view, row by row (view-major), each row given to
// `row(index, pixels)` once; rows run in parallel.
template <typename RowFn>
void render(const Scene& scene, const std::vector<View>& views, int resolution, RowFn&& row) {
  // Rays start outside everything, but no farther than kFarthestStart: a
  // wild vertex a million radii away would otherwise spend the depths'
  // single precision on the distance to it.
  const double start = 1.01 * std::clamp(scene.extent(), 1.0, kFarthestStart);
  const size_t rows = views.size() * static_cast<size_t>(resolution);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rows, 4), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<Pixel> pixels(resolution);
    for (size_t r = range.begin(); r != range.end(); ++r) {
      const View& view = views[r / resolution];
      const double y = (2.0 * static_cast<double>(r % resolution) + 1.0) / resolution - 1.0;
      for (int x = 0; x < resolution; ++x) {
        const double xs = (2.0 * x + 1.0) / resolution - 1.0;
        const Eigen::Vector3d origin = start * view.direction + xs * view.u + y * view.v;
        const Scene::Hit hit = scene.cast(origin, -view.direction);
        Pixel& p = pixels[x];
        if (hit.hit) {
          p.depth = static_cast<float>(hit.t - start);
          p.normal = scene.normal(hit.face).cast<float>();
        } else {
          p = Pixel{};
        }
      }
      row(r, pixels);
    }
  });
}

}  // namespace

struct VisualReference::State {
  const TriangleMesh* reference = nullptr;
  VisualOptions options;
  Frame frame;
  std::vector<View> views;
  std::vector<Pixel> pixels;  // the reference's render, row-major per view
  MeasuredSurface surface;
  std::unique_ptr<CgalFaceSearch> search;
  std::unique_ptr<EmbreeDevice> embree;
};

VisualReference::VisualReference(std::unique_ptr<State> state) : state_(std::move(state)) {}
VisualReference::VisualReference(VisualReference&&) noexcept = default;
VisualReference& VisualReference::operator=(VisualReference&&) noexcept = default;
VisualReference::~VisualReference() = default;

StatusOr<VisualReference> VisualReference::build(const TriangleMesh& reference, const VisualOptions& options) {
  const auto range = [](int low, int high) { return std::to_string(low) + ".." + std::to_string(high); };
  if (options.views < kMinVisualViews || options.views > kMaxVisualViews)
    return invalid_argument("visual measure: views must be " + range(kMinVisualViews, kMaxVisualViews) + ", got " +
                            std::to_string(options.views));
  if (options.resolution < kMinVisualResolution || options.resolution > kMaxVisualResolution)
    return invalid_argument("visual measure: resolution must be " + range(kMinVisualResolution, kMaxVisualResolution) +
                            ", got " + std::to_string(options.resolution));
  if (!(options.defect_degrees > 0.0 && options.defect_degrees < 180.0))
    return invalid_argument("visual measure: defect angle must be in (0, 180) degrees");
  auto state = std::make_unique<State>();
  state->reference = &reference;
  state->options = options;
  SRCODEC_ASSIGN_OR_RETURN(state->surface, measured_surface(reference, "reference"));
  state->frame = bounding_frame(state->surface);
  state->views = views_from(view_directions(options.views));
  state->embree = std::make_unique<EmbreeDevice>();
  if (!state->embree->device) return embree_error(nullptr, "start");
  SRCODEC_ASSIGN_OR_RETURN(std::unique_ptr<Scene> scene,
                           Scene::build(state->embree->device, state->surface, state->frame));
  const size_t res = static_cast<size_t>(options.resolution);
  state->pixels.resize(state->views.size() * res * res);
  render(*scene, state->views, options.resolution, [&](size_t row, const std::vector<Pixel>& pixels) {
    std::copy(pixels.begin(), pixels.end(), state->pixels.begin() + static_cast<std::ptrdiff_t>(row * res));
  });
  state->search = std::make_unique<CgalFaceSearch>(reference, state->surface.faces);
  return VisualReference(std::move(state));
}

StatusOr<VisualDifference> VisualReference::difference_to(const TriangleMesh& test) const {
  const State& s = *state_;
  SRCODEC_ASSIGN_OR_RETURN(const MeasuredSurface surface, measured_surface(test, "test"));
  SRCODEC_ASSIGN_OR_RETURN(std::unique_ptr<Scene> scene, Scene::build(s.embree->device, surface, s.frame));

  // Per row, so that the sums come out the same whatever the threads do.
  struct RowSums {
    double angle = 0, depth2 = 0;
    size_t both = 0, either = 0, defects = 0, agree = 0;
  };
  const size_t res = static_cast<size_t>(s.options.resolution);
  std::vector<RowSums> sums(s.views.size() * res);
  render(*scene, s.views, s.options.resolution, [&](size_t row, const std::vector<Pixel>& pixels) {
    RowSums& sum = sums[row];
    for (size_t x = 0; x < res; ++x) {
      const Pixel& a = s.pixels[row * res + x];
      const Pixel& b = pixels[x];
      if (!a.covered() && !b.covered()) continue;
      ++sum.either;
      if (!a.covered() || !b.covered()) {
        ++sum.defects;
        continue;
      }
      ++sum.both;
      const double angle = degrees_between(a.normal.cast<double>(), b.normal.cast<double>());
      sum.angle += angle;
      if (angle > s.options.defect_degrees) {
        ++sum.defects;
        continue;
      }
      // A ray grazing a silhouette can meet the front in one mesh and what
      // lies behind in the other: a depth jump that would swamp the RMS.
      // Depth is compared where both show the same surface.
      const double dz = static_cast<double>(a.depth) - static_cast<double>(b.depth);
      if (std::abs(dz) > kDepthJump) continue;
      ++sum.agree;
      sum.depth2 += dz * dz;
    }
  });
  RowSums total;
  for (const RowSums& r : sums) {
    total.angle += r.angle;
    total.depth2 += r.depth2;
    total.both += r.both;
    total.either += r.either;
    total.defects += r.defects;
    total.agree += r.agree;
  }

  VisualDifference out;
  out.pixels = total.either;
  out.defect_share = total.either ? static_cast<double>(total.defects) / total.either : 0.0;
  out.mean_normal_degrees = total.both ? total.angle / total.both : 0.0;
  // Depths are in units of the bounding radius: the peak, the diagonal, is 2.
  const double depth_rms = total.agree ? std::sqrt(total.depth2 / total.agree) : 0.0;
  out.depth_psnr = psnr_db(2.0, depth_rms);

  // Turned over: each test triangle judged at its centroid by the nearest
  // reference triangle's normal, with the one definition of a fold.
  std::vector<char> turned(surface.faces.size(), 0);
  const TriangleMesh& ref = *s.reference;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, surface.faces.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const auto& t = test.triangles[surface.faces[i]];
      const Eigen::Vector3d &p0 = test.positions[t[0]], &p1 = test.positions[t[1]], &p2 = test.positions[t[2]];
      const uint32_t nearest = s.search->nearest_face((p0 + p1 + p2) / 3.0);
      turned[i] = folded(facing(p0, p1, p2, triangle_normal(ref.positions, ref.triangles[nearest]))) ? 1 : 0;
    }
  });
  double turned_area = 0.0;
  for (size_t i = 0; i < turned.size(); ++i)
    if (turned[i]) turned_area += surface.areas[i];
  out.turned_over_share = turned_area / surface.total_area;
  return out;
}

// Directions on a Fibonacci lattice (Swinbank & Purser 2006; González 2010):
// n points spread evenly over the sphere, none at the poles.
std::vector<Eigen::Vector3d> view_directions(int views) {
  const double golden_angle = kPi * (3.0 - std::sqrt(5.0));
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < views; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / views;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    out.emplace_back(r * std::cos(golden_angle * i), r * std::sin(golden_angle * i), z);
  }
  return out;
}

StatusOr<VisualDifference> visual_difference(const TriangleMesh& reference, const TriangleMesh& test,
                                             const VisualOptions& options) {
  SRCODEC_ASSIGN_OR_RETURN(const VisualReference visual, VisualReference::build(reference, options));
  return visual.difference_to(test);
}

}  // namespace srcodec
