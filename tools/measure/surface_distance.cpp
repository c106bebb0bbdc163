#include "tools/measure/surface_distance.h"

#include <CGAL/AABB_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/property_map.h>

#include <cstddef>
#include <vector>

namespace srcodec {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;

// ---------------------------------------------------------------------------
// The AABB tree over a surface. Primitives hold only a 32-bit face index; the
// triangle is built on the fly from the mesh (CGAL's "shared data"
// primitive): no cached triangle, 72 bytes a face less.
//
// Distance queries start from a hint, the nearest of a set of points on the
// surface found in a KD tree. CGAL's default puts one point per face in it,
// which costs nearly as much to build as the AABB tree itself; the centroid
// of every kHintStride-th face is a quarter of that for slightly longer
// queries. The hints only speed the search up: the distance is the same.

constexpr size_t kHintStride = 4;

inline Point to_point(const Eigen::Vector3d& p) { return Point(p.x(), p.y(), p.z()); }

struct FaceTriangleMap {
  using key_type = uint32_t;
  using value_type = Triangle;
  using reference = Triangle;
  using category = boost::readable_property_map_tag;

  const TriangleMesh* mesh = nullptr;

  friend Triangle get(const FaceTriangleMap& map, uint32_t face) {
    const auto& t = map.mesh->triangles[face];
    return Triangle(to_point(map.mesh->positions[static_cast<size_t>(t[0])]),
                    to_point(map.mesh->positions[static_cast<size_t>(t[1])]),
                    to_point(map.mesh->positions[static_cast<size_t>(t[2])]));
  }
};

// The reference point, along which CGAL splits the primitives when building
// the tree: the face's first corner, read without arithmetic.
struct FaceCornerMap {
  using key_type = uint32_t;
  using value_type = Point;
  using reference = Point;
  using category = boost::readable_property_map_tag;

  const TriangleMesh* mesh = nullptr;

  friend Point get(const FaceCornerMap& map, uint32_t face) {
    return to_point(map.mesh->positions[static_cast<size_t>(map.mesh->triangles[face][0])]);
  }
};

using Primitive = CGAL::AABB_primitive<uint32_t, FaceTriangleMap, FaceCornerMap,
                                       CGAL::Tag_true /*maps in the tree*/,
                                       CGAL::Tag_false /*no cached datum*/>;
using Traits = CGAL::AABB_traits<Kernel, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;

}  // namespace

struct CgalFaceSearch::Search {
  Tree tree;
};

// Builds the tree and its KD tree of hints eagerly: CGAL builds both lazily
// on the first query otherwise, which must not happen inside the parallel
// loop. After this the tree is only read, and queries may run concurrently.
CgalFaceSearch::CgalFaceSearch(const TriangleMesh& mesh, const std::vector<uint32_t>& faces)
    : search_(std::make_unique<Search>()) {
  Tree& tree = search_->tree;
  tree.insert(faces.begin(), faces.end(), FaceTriangleMap{&mesh}, FaceCornerMap{&mesh});
  tree.build();
  std::vector<Tree::Point_and_primitive_id> hints;
  hints.reserve(faces.size() / kHintStride + 1);
  for (size_t i = 0; i < faces.size(); i += kHintStride) {
    const auto& t = mesh.triangles[faces[i]];
    const Eigen::Vector3d centroid = (mesh.positions[static_cast<size_t>(t[0])] +
                                      mesh.positions[static_cast<size_t>(t[1])] +
                                      mesh.positions[static_cast<size_t>(t[2])]) /
                                     3.0;
    hints.emplace_back(to_point(centroid), faces[i]);
  }
  tree.accelerate_distance_queries(hints.begin(), hints.end());
}

CgalFaceSearch::~CgalFaceSearch() = default;

double CgalFaceSearch::squared_distance(const Eigen::Vector3d& p) const {
  return search_->tree.squared_distance(to_point(p));  // hint from the KD tree
}

uint32_t CgalFaceSearch::nearest_face(const Eigen::Vector3d& p) const {
  return search_->tree.closest_point_and_primitive(to_point(p)).second;
}

std::unique_ptr<NearestSurfacePoint> cgal_search(const TriangleMesh& mesh, const std::vector<uint32_t>& faces) {
  return std::make_unique<CgalFaceSearch>(mesh, faces);
}

StatusOr<SurfaceDistance> cgal_surface_distance(const TriangleMesh& reference, const TriangleMesh& test,
                                                const SurfaceDistanceOptions& options) {
  return surface_distance(reference, test, options, cgal_search);
}

}  // namespace srcodec
