#include "tools/measure/visual_difference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "remesh/folds.h"
#include "remesh/geometry.h"
#include "remesh/surface_distance.h"
#include "tools/measure/surface_distance.h"

namespace srcodec {
namespace {

// In the frame's units (the reference's bounding radius): a depth difference
// over this is a different surface seen, not the same one moved.
constexpr double kDepthJump = 0.1;

}  // namespace

struct VisualReference::State {
  const TriangleMesh* reference = nullptr;
  VisualOptions options;
  RenderFrame frame;
  std::vector<View> views;
  std::vector<Pixel> pixels;  // the reference's render, row-major per view
  MeasuredSurface surface;
  std::unique_ptr<CgalFaceSearch> search;
  std::optional<RayCaster> caster;
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
  SRCODEC_ASSIGN_OR_RETURN(state->caster, RayCaster::start());
  const size_t res = static_cast<size_t>(options.resolution);
  state->pixels.resize(state->views.size() * res * res);
  const auto keep_row = [&](size_t row, const std::vector<Pixel>& pixels) {
    std::copy(pixels.begin(), pixels.end(), state->pixels.begin() + static_cast<std::ptrdiff_t>(row * res));
  };
  SRCODEC_RETURN_IF_ERROR(
      state->caster->render(state->surface, state->frame, state->views, options.resolution, keep_row));
  state->search = std::make_unique<CgalFaceSearch>(reference, state->surface.faces);
  return VisualReference(std::move(state));
}

StatusOr<VisualDifference> VisualReference::difference_to(const TriangleMesh& test) const {
  const State& s = *state_;
  SRCODEC_ASSIGN_OR_RETURN(const MeasuredSurface surface, measured_surface(test, "test"));

  // Per row, so that the sums come out the same whatever the threads do.
  struct RowSums {
    double angle = 0, depth2 = 0;
    size_t both = 0, either = 0, defects = 0, agree = 0;
  };
  const size_t res = static_cast<size_t>(s.options.resolution);
  std::vector<RowSums> sums(s.views.size() * res);
  const auto compare_row = [&](size_t row, const std::vector<Pixel>& pixels) {
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
  };
  SRCODEC_RETURN_IF_ERROR(s.caster->render(surface, s.frame, s.views, s.options.resolution, compare_row));
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

StatusOr<VisualDifference> visual_difference(const TriangleMesh& reference, const TriangleMesh& test,
                                             const VisualOptions& options) {
  SRCODEC_ASSIGN_OR_RETURN(const VisualReference visual, VisualReference::build(reference, options));
  return visual.difference_to(test);
}

}  // namespace srcodec
