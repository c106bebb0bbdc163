// The encoding half of the crease coder (codec/crease_coder.h).
#include <algorithm>
#include <string>

#include "codec/crease_coder.h"
#include "codec/crease_model.h"
#include "codec/range_coder.h"

namespace srcodec {

using namespace crease_detail;

StatusOr<std::vector<uint8_t>> encode_creases(const std::vector<std::array<int32_t, 3>>& triangles,
                                              const std::vector<std::array<int32_t, 2>>& creases) {
  int32_t vertex_count = 0;
  for (const auto& t : triangles) vertex_count = std::max({vertex_count, t[0] + 1, t[1] + 1, t[2] + 1});
  ArithmeticEncoder enc;
  std::vector<BitModel> models(kContexts);
  size_t found = 0;
  const auto is_crease = [&](int32_t a, int32_t b) {
    return std::binary_search(creases.begin(), creases.end(), std::array<int32_t, 2>{a, b});
  };
  SRCODEC_RETURN_IF_ERROR(walk_edges(triangles, vertex_count, [&](int32_t a, int32_t b, int ctx, int& flag) {
    flag = is_crease(a, b) ? 1 : 0;
    found += flag;
    enc.encode(flag, models[ctx]);
    return ok_status();
  }));
  if (found != creases.size()) {
    for (const auto& e : creases) {
      bool edge = false;
      for (const auto& t : triangles)
        for (int k = 0; k < 3 && !edge; ++k)
          edge = std::minmax(t[k], t[(k + 1) % 3]) == std::minmax(e[0], e[1]);
      if (!edge)
        return invalid_argument("creases: (" + std::to_string(e[0]) + ", " + std::to_string(e[1]) +
                                ") is not an edge of the base mesh");
    }
    return invalid_argument("creases: " + std::to_string(creases.size()) + " listed, " + std::to_string(found) +
                            " found among the base edges (they must be sorted, with a < b and no repeats)");
  }
  return enc.finish();
}

}  // namespace srcodec
