// The encoder as a list of named steps, shared by the public encode()
// (codec/encoder_api.cpp) and `srcodec encode`: remesh the cleaned input,
// code the whole embedded stream, choose the cut the rate asks for, cut it,
// and measure the file kept against the input.
#pragma once

#include <srcodec/encoder.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "codec/rate_control.h"
#include "codec/srm_codec.h"
#include "format/mesh.h"
#include "format/status.h"
#include "remesh/remesher.h"

namespace srcodec {

struct MeshEncodeOptions {
  RemeshOptions remesh;
  SrmEncodeOptions coding;
  Rate rate;  // the knee by default
  // Samples per surface for the PSNR of the file kept (the cuts compared on
  // the way use kRateControlSamples).
  size_t samples = kRateControlSamples;
  // Called after each step (EncodeProgress: the remesher's main steps, then
  // "remesh", "code", "rate", "measure"), beside remesh.progress; may be
  // empty.
  std::function<void(const EncodeProgress&)> progress;
};

struct MeshEncodeResult {
  std::vector<uint8_t> file;
  SrmHeader header;                // of the whole stream (levels, base vertices)
  size_t crease_edges = 0;         // base edges the remesh marks sharp (the file's crease chunk)
  uint64_t full_stream_bytes = 0;
  uint64_t minimum_bytes = 0;      // header, base mesh, creases and flags: the smallest cut
  double psnr = 0;                 // of `file` against the input, with `samples`
  Knee knee;                       // with Rate::Kind::kKnee: where the search stopped
  RemeshReport remesh;
  double seconds_remesh = 0, seconds_coding = 0, seconds_rate = 0;
};

// `input` is a cleaned mesh (clean_mesh). Errors say what to change when the
// rate cannot be met (a budget below the smallest file, a PSNR beyond the
// whole stream's).
StatusOr<MeshEncodeResult> encode_mesh(const TriangleMesh& input, const MeshEncodeOptions& options);

}  // namespace srcodec
