// The decoding half of the refinement-flag coder (codec/flags_coder.h).
#include <string>

#include "codec/flags_coder.h"
#include "codec/flags_model.h"
#include "codec/range_coder.h"

namespace srcodec {

using namespace flags_detail;

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
