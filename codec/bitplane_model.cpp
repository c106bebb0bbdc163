#include "codec/bitplane_model.h"

#include <string>

namespace srcodec {
namespace bitplane_detail {
namespace {

// True when the forest's nodes come in runs of three as ForestIndex::group says.
bool grouped_by_three(const CoefficientForest& f) {
  const size_t n = f.parent.size();
  if (n == 0 || n % 3 != 0) return false;
  for (size_t k = 0; k < n; k += 3) {
    const int32_t p = f.parent[k];
    if (p >= 0 && p % 3 != 0) return false;
    for (size_t c = 1; c < 3; ++c)
      if (f.level[k + c] != f.level[k] || f.parent[k + c] != (p < 0 ? -1 : p + static_cast<int32_t>(c))) return false;
  }
  return true;
}

}  // namespace

ForestIndex build_index(const CoefficientForest& f) {
  ForestIndex x;
  const size_t n = f.parent.size();
  x.max_level = n == 0 ? 0 : f.level.back();
  x.level_begin.assign(static_cast<size_t>(x.max_level) + 2, static_cast<uint32_t>(n));
  for (size_t i = n; i-- > 0;) x.level_begin[f.level[i]] = static_cast<uint32_t>(i);
  for (int l = x.max_level; l >= 1; --l) x.level_begin[l] = std::min(x.level_begin[l], x.level_begin[l + 1]);
  x.level_begin[0] = 0;

  x.group = grouped_by_three(f) ? 3 : 1;
  const size_t groups = n / x.group;
  // Counted into child_begin[p + 2] and summed, child_begin[p + 1] is where
  // group p's children start; filling moves it to where they end, which is
  // child_begin[p + 1]'s final value (no second array of cursors).
  x.child_begin.assign(groups + 2, 0);
  for (size_t g = 0; g < groups; ++g) {
    const int32_t p = f.parent[g * x.group];
    if (p >= 0) ++x.child_begin[static_cast<size_t>(p) / x.group + 2];
  }
  for (size_t i = 2; i <= groups + 1; ++i) x.child_begin[i] += x.child_begin[i - 1];
  x.children.resize(x.child_begin[groups + 1]);
  for (size_t g = 0; g < groups; ++g) {
    const int32_t p = f.parent[g * x.group];
    if (p >= 0) x.children[x.child_begin[static_cast<size_t>(p) / x.group + 1]++] = static_cast<uint32_t>(g);
  }
  x.child_begin.pop_back();

  std::vector<int32_t> dense(256 * kMaxContextClasses, -1);
  x.model_set.resize(n);
  for (size_t i = 0; i < n; ++i) {
    int32_t& id = dense[f.level[i] * kMaxContextClasses + f.context_class[i]];
    if (id < 0) id = static_cast<int32_t>(x.model_sets++);
    x.model_set[i] = static_cast<uint16_t>(id);
  }
  return x;
}

}  // namespace bitplane_detail

Status validate_forest(const CoefficientForest& forest) {
  const size_t n = forest.parent.size();
  if (forest.level.size() != n || forest.context_class.size() != n)
    return invalid_argument("coefficient forest: " + std::to_string(n) + " parents but " +
                            std::to_string(forest.level.size()) + " levels and " +
                            std::to_string(forest.context_class.size()) + " context classes");
  if (n > (size_t{1} << 31) - 1) return invalid_argument("coefficient forest: too many nodes");
  for (size_t i = 0; i < n; ++i) {
    const auto where = [i] { return "coefficient forest, node " + std::to_string(i) + ": "; };
    const int level = forest.level[i];
    if (level < 1) return invalid_argument(where() + "level 0 (levels start at 1)");
    if (i > 0 && level < forest.level[i - 1])
      return invalid_argument(where() + "level " + std::to_string(level) + " after level " +
                              std::to_string(forest.level[i - 1]) + " (nodes must be sorted by level)");
    if (forest.context_class[i] >= kMaxContextClasses)
      return invalid_argument(where() + "context class " + std::to_string(forest.context_class[i]) + " >= " +
                              std::to_string(kMaxContextClasses));
    const int32_t p = forest.parent[i];
    if (p < -1 || (p >= 0 && static_cast<size_t>(p) >= i))
      return invalid_argument(where() + "parent " + std::to_string(p) + " is not -1 or an earlier node");
    if (p >= 0 && forest.level[static_cast<size_t>(p)] >= level)
      return invalid_argument(where() + "parent " + std::to_string(p) + " has level " +
                              std::to_string(forest.level[static_cast<size_t>(p)]) + ", not below " +
                              std::to_string(level));
  }
  return ok_status();
}

}  // namespace srcodec
