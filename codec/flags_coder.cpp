#include "codec/flags_coder.h"

#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>

#include "codec/range_coder.h"

namespace srcodec {
namespace {

constexpr int kContextLevels = 8;
constexpr int kContextsPerLevel = 5;  // level 0: the previous flag (0, 1); finer: split earlier siblings (0..3)

// Flags of triangles that share a parent are correlated (a region is refined
// or not), so the context is how many earlier siblings were split.
int flag_context(const TriangleHierarchy& h, int32_t node, int previous_flag) {
  const TriangleHierarchy::Node& n = h.nodes()[node];
  const int level = std::min<int>(n.level, kContextLevels - 1);
  if (n.parent < 0) return level * kContextsPerLevel + previous_flag;
  const int32_t first = h.nodes()[n.parent].first_child;
  int split = 0;
  for (int32_t s = first; s < node; ++s) split += h.nodes()[s].first_child >= 0;
  return level * kContextsPerLevel + split;
}

// One pass: every leaf of level `level`, in node order (the order grows as
// splits append nodes), gets a flag from `decide`; a node that closure split
// before its turn gets none. `after_split` runs after each split.
template <typename Decide, typename AfterSplit>
Status replay_level(TriangleHierarchy& h, int32_t level, size_t max_vertices, Decide&& decide,
                    AfterSplit&& after_split) {
  int previous = 0;
  for (size_t n = 0; n < h.nodes().size(); ++n) {
    const TriangleHierarchy::Node& node = h.nodes()[n];
    if (node.level != level || node.first_child >= 0) continue;
    const int32_t id = static_cast<int32_t>(n);
    int flag = 0;
    SRCODEC_RETURN_IF_ERROR(decide(id, flag_context(h, id, previous), flag));
    previous = flag;
    if (!flag) continue;
    h.split(id);
    if (static_cast<size_t>(h.vertex_count()) > max_vertices)
      return parse_error("level " + std::to_string(level + 1) + " would have more than " +
                         std::to_string(max_vertices) + " vertices");
    after_split();
  }
  return ok_status();
}

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

Status decode_refinement_level(TriangleHierarchy& hierarchy, int32_t level, const uint8_t* data, size_t size,
                               size_t max_vertices) {
  ArithmeticDecoder dec(data, size);
  std::vector<BitModel> models(kContextLevels * kContextsPerLevel);
  const bool all = dec.decode_raw(1) != 0;
  const std::string where = "flags of level " + std::to_string(level);
  if (!dec.ok()) return parse_error(where + ": the chunk is empty");
  Status status = replay_level(
      hierarchy, level, max_vertices,
      [&](int32_t, int ctx, int& flag) {
        flag = all ? 1 : dec.decode(models[ctx]);
        return dec.ok() ? ok_status() : parse_error(where + ": the chunk ends before its last flag");
      },
      [] {});
  return status;
}

}  // namespace srcodec
