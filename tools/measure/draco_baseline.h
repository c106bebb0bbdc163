// Draco (google/draco, Debian's libdraco) in-process: the baseline every
// srcodec rate-distortion figure is compared with. Positions and connectivity
// only, positions quantized to `quantization_bits`.
#pragma once

#include <string>

#include "format/mesh.h"
#include "format/status.h"

namespace srcodec {

struct DracoOptions {
  int quantization_bits = 11;  // 1..30 (Draco's own limits); 6..16 in rd sweeps
  int compression_level = 10;  // 0..10; 10 = Draco's best compression (edgebreaker, valence coding)
};

struct DracoRoundTrip {
  std::string encoded;   // the .drc bytes
  TriangleMesh decoded;  // what Draco's decoder gives back
  double encode_ms = 0;
  double decode_ms = 0;
};

StatusOr<DracoRoundTrip> draco_round_trip(const TriangleMesh& mesh, const DracoOptions& options = {});

// Decodes .drc bytes into a triangle mesh (positions and faces).
StatusOr<TriangleMesh> draco_decode(const std::string& bytes);

}  // namespace srcodec
