#include "tools/measure/ray_cast.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "remesh/geometry.h"

namespace srcodec {
namespace {

constexpr double kPi = 3.14159265358979323846;
// The farthest from the centre rays start, in the frame's units.
constexpr double kFarthestStart = 4.0;

Status embree_error(RTCDevice device, const std::string& what) {
  return internal_error("ray casting: Embree failed to " + what + " (error " +
                        std::to_string(static_cast<int>(rtcGetDeviceError(device))) + ")");
}

// One mesh's triangles of positive area in an Embree scene, in the frame.
class Scene {
 public:
  static StatusOr<std::unique_ptr<Scene>> build(RTCDevice device, const MeasuredSurface& surface,
                                                const RenderFrame& frame) {
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
  // mesh that set the frame; another may reach farther).
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

}  // namespace

RenderFrame bounding_frame(const MeasuredSurface& surface) {
  const TriangleMesh& mesh = *surface.mesh;
  Eigen::AlignedBox3d box;
  for (uint32_t f : surface.faces)
    for (int32_t v : mesh.triangles[f]) box.extend(mesh.positions[v]);
  RenderFrame frame;
  frame.center = box.center();
  frame.radius = 0.5 * box.diagonal().norm();
  if (!(frame.radius > 0.0)) frame.radius = 1.0;  // cannot happen with positive area; kept finite anyway
  return frame;
}

View view_along(const Eigen::Vector3d& direction, const Eigen::Vector3d& up) {
  View view;
  view.direction = direction;
  view.u = up.cross(direction).normalized();
  view.v = direction.cross(view.u);
  return view;
}

std::vector<View> views_from(const std::vector<Eigen::Vector3d>& directions) {
  std::vector<View> views;
  for (const Eigen::Vector3d& d : directions)
    views.push_back(view_along(d, std::abs(d.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX()));
  return views;
}

// Swinbank & Purser 2006; González 2010.
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

struct RayCaster::Device {
  RTCDevice device = nullptr;
  Device() : device(rtcNewDevice(nullptr)) {}
  ~Device() {
    if (device) rtcReleaseDevice(device);
  }
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;
};

StatusOr<RayCaster> RayCaster::start() {
  auto device = std::make_shared<Device>();
  if (!device->device) return embree_error(nullptr, "start");
  return RayCaster(std::move(device));
}

Status RayCaster::render(const MeasuredSurface& surface, const RenderFrame& frame, const std::vector<View>& views,
                         int resolution, const RowSink& row) const {
  SRCODEC_ASSIGN_OR_RETURN(const std::unique_ptr<Scene> scene, Scene::build(device_->device, surface, frame));
  // Rays start outside everything, but no farther than kFarthestStart: a
  // wild vertex a million radii away would otherwise spend the depths'
  // single precision on the distance to it.
  const double start = 1.01 * std::clamp(scene->extent(), 1.0, kFarthestStart);
  const size_t rows = views.size() * static_cast<size_t>(resolution);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rows, 4), [&](const tbb::blocked_range<size_t>& range) {
    std::vector<Pixel> pixels(resolution);
    for (size_t r = range.begin(); r != range.end(); ++r) {
      const View& view = views[r / resolution];
      const double y = (2.0 * static_cast<double>(r % resolution) + 1.0) / resolution - 1.0;
      for (int x = 0; x < resolution; ++x) {
        const double xs = (2.0 * x + 1.0) / resolution - 1.0;
        const Eigen::Vector3d origin = start * view.direction + xs * view.u + y * view.v;
        const Scene::Hit hit = scene->cast(origin, -view.direction);
        Pixel& p = pixels[x];
        if (hit.hit) {
          p.depth = static_cast<float>(hit.t - start);
          p.normal = scene->normal(hit.face).cast<float>();
        } else {
          p = Pixel{};
        }
      }
      row(r, pixels);
    }
  });
  return ok_status();
}

}  // namespace srcodec
