// The encoding half of the refinement-flag coder (codec/flags_coder.h): the
// remesher's hierarchy replayed on the decoder's base mesh, flag by flag.
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "codec/flags_coder.h"
#include "codec/flags_model.h"
#include "codec/range_coder.h"

namespace srcodec {

using namespace flags_detail;

namespace {

uint64_t edge_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

std::array<int32_t, 3> sorted(std::array<int32_t, 3> t) {
  std::sort(t.begin(), t.end());
  return t;
}

// Keeps the replayed hierarchy's nodes and vertices linked to the original's.
class OriginalLink {
 public:
  OriginalLink(const TriangleHierarchy& original, const std::vector<int32_t>& base_vertex,
               const std::vector<int32_t>& base_triangle)
      : original_(original), vertex_(base_vertex), node_(base_triangle) {
    for (int32_t v = original.base_vertex_count(); v < original.vertex_count(); ++v) {
      const auto e = original.parent_edge(v);
      midpoint_.emplace(edge_key(e[0], e[1]), v);
    }
  }
  int32_t node(int32_t replayed) const { return node_[replayed]; }
  const std::vector<int32_t>& vertices() const { return vertex_; }

  // Links what the last split appended.
  Status catch_up(const TriangleHierarchy& h) {
    for (int32_t v = static_cast<int32_t>(vertex_.size()); v < h.vertex_count(); ++v) {
      const auto e = h.parent_edge(v);
      const auto it = midpoint_.find(edge_key(vertex_[e[0]], vertex_[e[1]]));
      if (it == midpoint_.end()) return internal_error("replayed vertex " + std::to_string(v) + " is not in the remesh");
      vertex_.push_back(it->second);
    }
    for (size_t n = node_.size(); n < h.nodes().size(); ++n) {
      const TriangleHierarchy::Node& node = h.nodes()[n];
      const TriangleHierarchy::Node& parent = original_.nodes()[node_[node.parent]];
      const auto want = sorted({vertex_[node.v[0]], vertex_[node.v[1]], vertex_[node.v[2]]});
      int32_t match = -1;
      for (int c = 0; c < 4 && parent.first_child >= 0; ++c)
        if (sorted(original_.nodes()[parent.first_child + c].v) == want) match = parent.first_child + c;
      if (match < 0) return internal_error("replayed triangle " + std::to_string(n) + " is not in the remesh");
      node_.push_back(match);
    }
    return ok_status();
  }

 private:
  const TriangleHierarchy& original_;
  std::vector<int32_t> vertex_;  // replayed -> original
  std::vector<int32_t> node_;
  std::unordered_map<uint64_t, int32_t> midpoint_;  // lookups only: its order never shows
};

}  // namespace

StatusOr<ReplayedHierarchy> encode_refinement(const TriangleHierarchy& original, int32_t levels,
                                              const std::vector<std::array<int32_t, 3>>& base,
                                              const std::vector<int32_t>& base_to_original_vertex,
                                              const std::vector<int32_t>& base_to_original_triangle) {
  StatusOr<TriangleHierarchy> created = TriangleHierarchy::create(original.base_vertex_count(), base);
  if (!created.ok()) return created.status().with_context("replaying the refinement");
  ReplayedHierarchy out{std::move(created.value()), {}, {}};
  TriangleHierarchy& h = out.hierarchy;
  OriginalLink link(original, base_to_original_vertex, base_to_original_triangle);
  const auto is_split = [&](int32_t n) { return original.nodes()[link.node(n)].first_child >= 0; };
  for (int32_t level = 0; level < levels; ++level) {
    bool all = true;
    for (size_t n = 0; n < h.nodes().size(); ++n)
      if (h.nodes()[n].level == level && h.nodes()[n].first_child < 0) all = all && is_split(static_cast<int32_t>(n));
    ArithmeticEncoder enc;
    std::vector<BitModel> models(kContextLevels * kContextsPerLevel);
    enc.encode_raw(all ? 1 : 0, 1);
    Status status = replay_level(
        h, level, SIZE_MAX,
        [&](int32_t n, int ctx, int& flag) {
          flag = is_split(n) ? 1 : 0;
          if (!all) enc.encode(flag, models[ctx]);
          return ok_status();
        },
        [&] { (void)0; });
    SRCODEC_RETURN_IF_ERROR(status);
    // Link after the pass: catch_up needs each new node's parent linked, and
    // nodes are appended in creation order, parents first.
    SRCODEC_RETURN_IF_ERROR(link.catch_up(h));
    out.flags.push_back(enc.finish());
  }
  if (h.nodes().size() != original.nodes().size() || h.vertex_count() != original.vertex_count())
    return internal_error("the replayed hierarchy has " + std::to_string(h.nodes().size()) + " triangles, the remesh " +
                          std::to_string(original.nodes().size()));
  out.to_original_vertex = link.vertices();
  return out;
}

}  // namespace srcodec
