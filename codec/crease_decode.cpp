// The decoding half of the crease coder (codec/crease_coder.h).
#include <algorithm>
#include <string>

#include "codec/crease_coder.h"
#include "codec/crease_model.h"
#include "codec/range_coder.h"

namespace srcodec {

using namespace crease_detail;

StatusOr<std::vector<std::array<int32_t, 2>>> decode_creases(const std::vector<std::array<int32_t, 3>>& triangles,
                                                              int32_t vertex_count, const uint8_t* data,
                                                              size_t size) {
  ArithmeticDecoder dec(data, size);
  std::vector<BitModel> models(kContexts);
  std::vector<std::array<int32_t, 2>> creases;
  size_t edges = 0;
  SRCODEC_RETURN_IF_ERROR(walk_edges(triangles, vertex_count, [&](int32_t a, int32_t b, int ctx, int& flag) {
    flag = dec.decode(models[ctx]);
    if (!dec.ok())
      return parse_error("creases: the chunk (" + std::to_string(size) + " bytes) ends before the flag of base edge " +
                         std::to_string(edges) + " (" + std::to_string(a) + ", " + std::to_string(b) + ")");
    ++edges;
    if (flag) creases.push_back({a, b});
    return ok_status();
  }));
  // The decoder has read 4 bytes ahead of its last decision; the encoder's
  // stream ends 1 or 2 bytes after it (range_encode.cpp writes only the bytes
  // that pin it). Bytes the decoder never reached are not the encoder's.
  if (dec.bytes_consumed() != size)
    return parse_error("creases: " + std::to_string(size - dec.bytes_consumed()) + " bytes after the flags of the " +
                       std::to_string(edges) + " base edges");
  std::sort(creases.begin(), creases.end());
  return creases;
}

}  // namespace srcodec
