#include "codec/srm_layout.h"

#include <algorithm>

namespace srcodec {

ForestLayout build_forest(const TriangleHierarchy& h, int levels) {
  ForestLayout out;
  const int32_t vertex_count = h.vertex_count();
  // The vertices of levels 0 .. `levels`, by level, each level in id order.
  // A decoder's replay numbers them so already (level by level): then they
  // are just listed; a remesher's adaptive hierarchy need not, and gets a
  // counting sort.
  std::vector<size_t> level_begin(levels + 2, 0);
  bool sorted = true;
  int32_t previous = 0;
  for (int32_t v = 0; v < vertex_count; ++v) {
    const int32_t l = h.vertex_level(v);
    if (l > levels) continue;
    ++level_begin[l + 1];
    sorted = sorted && l >= previous;
    previous = l;
  }
  for (int f = 0; f <= levels; ++f) level_begin[f + 1] += level_begin[f];
  out.vertex.resize(level_begin[levels + 1]);
  {
    std::vector<size_t> fill(level_begin.begin(), level_begin.end() - 1);
    size_t k = 0;
    for (int32_t v = 0; v < vertex_count; ++v) {
      const int32_t l = h.vertex_level(v);
      if (l <= levels) out.vertex[sorted ? k++ : fill[l]++] = v;
    }
  }
  const size_t nodes = out.vertex.size() * kSrmComponents;
  // Written through pointers: push_back's capacity checks cost more than the
  // work on the decoder's path.
  out.forest.parent.resize(nodes);
  out.forest.level.resize(nodes);
  out.forest.context_class.resize(nodes);
  out.first_node.assign(vertex_count, -1);
  int32_t* parent_of = out.forest.parent.data();
  uint8_t* level_of = out.forest.level.data();
  uint8_t* class_of = out.forest.context_class.data();
  for (size_t k = 0; k < out.vertex.size(); ++k) {
    const int32_t v = out.vertex[k];
    const int32_t f = h.vertex_level(v);
    int32_t parent = -1;
    if (f >= 2) {
      const auto e = h.parent_edge(v);
      const int32_t la = h.vertex_level(e[0]), lb = h.vertex_level(e[1]);
      const int32_t p = (la != lb) ? (la > lb ? e[0] : e[1]) : std::max(e[0], e[1]);
      parent = out.first_node[p];
    }
    const size_t first = k * kSrmComponents;
    out.first_node[v] = static_cast<int32_t>(first);
    for (int c = 0; c < kSrmComponents; ++c) {
      parent_of[first + c] = parent < 0 ? -1 : parent + c;
      level_of[first + c] = static_cast<uint8_t>(f + 1);
      class_of[first + c] = static_cast<uint8_t>(f * kSrmComponents + c);
    }
  }
  return out;
}

// quant_step x scale(f, c) for every (f, c), at index 3f + c.
std::vector<double> step_table(const SrmHeader& h) {
  std::vector<double> steps;
  for (int f = 0; f <= h.levels; ++f)
    for (int c = 0; c < kSrmComponents; ++c) steps.push_back(h.quant_step * h.scale(f, c));
  return steps;
}

QuantizationGrid grid_of(const SrmHeader& h) {
  QuantizationGrid g;
  g.origin = h.bbox_min;
  g.step = h.grid_step;
  g.bits = h.base_bits;
  return g;
}

}  // namespace srcodec
