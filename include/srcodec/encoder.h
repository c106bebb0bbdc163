// Encoding a triangle mesh into a progressive .srm file: an adaptive
// semi-regular remesh (Kammoun, Payan, Antonini), a lifted Butterfly wavelet
// transform and embedded bit-plane coding, cut at the rate asked for. Part of
// srcodec::encoder (OpenMesh, oneTBB and nanoflann underneath).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include <srcodec/mesh.h>
#include <srcodec/status.h>

namespace srcodec {

// Where the remesh refines.
enum class Adaptivity {
  kUniform,        // every triangle, every level
  kVertexCount,    // the paper's Eq. 5: where every corner's Voronoi cell holds more than `threshold` input vertices
  kMeasuredError,  // refine uniformly, then undo the splits that gain least while the estimated PSNR stays within
                   // `max_loss_db` of the uniform remesh's
};

// Whether the remesh keeps the input's sharp creases (where the surface
// folds by more than 30 degrees): as base edges, their corners as base
// vertices, recorded in the file and predicted along by the wavelet, so
// that they stay sharp at every rate.
enum class Creases {
  kAuto,  // where they are a real share of the shape (CAD parts): 7.5% of the base mesh's edges
  kKeep,  // every crease long enough for the base mesh to follow (a base edge)
  kOff,   // none
};

// How much of the embedded stream the file keeps: one of these.
struct Rate {
  enum class Kind {
    kKnee,          // where one more bit per input vertex would gain less than 1 dB
    kBytes,         // the largest file of at most `value` bytes
    kBitsPerVertex, // the largest file of at most `value` bits per input vertex
    kPsnr,          // the smallest file whose PSNR against the input reaches `value` dB
  };
  Kind kind = Kind::kKnee;
  double value = 0;

  static Rate knee() { return {}; }
  static Rate bytes(uint64_t n) { return {Kind::kBytes, static_cast<double>(n)}; }
  static Rate bits_per_vertex(double bpv) { return {Kind::kBitsPerVertex, bpv}; }
  static Rate psnr(double db) { return {Kind::kPsnr, db}; }
};

// A step of the encode that has just finished. The remesh (most of the
// time) reports "oversample", "sites", "base mesh", "level" (once per level), "fit",
// "coarsen" (with kMeasuredError), "untangle" (maybe several times) and
// "slivers", then "remesh" when it is done; then "code" (the whole embedded
// stream), "rate" (the cut chosen) and "measure" (the file's PSNR).
struct EncodeProgress {
  const char* stage = "";
  int level = 0;       // with "level": the refinement level just built
  double seconds = 0;  // since encode() began
};

struct EncodeOptions {
  // Refinement levels above the base mesh, 0 .. 12. -1: 4, or fewer for an
  // input too small for 4 (none below 100 vertices).
  int levels = -1;
  // Vertices of the base mesh; 0: chosen from the input's size and the
  // levels (100 .. 4000).
  size_t base_vertices = 0;
  Adaptivity adaptivity = Adaptivity::kUniform;
  double threshold = 0.0;        // kVertexCount: input vertices per Voronoi cell, >= 0
  double max_loss_db = 0.5;      // kMeasuredError: 0.01 .. 60
  double deepen_fraction = 0.0;  // kMeasuredError: first split once more this share of the finest triangles
                                 // holding the most error (0 .. 1); the file may then have one level more
  Creases creases = Creases::kAuto;
  Rate rate;                     // the knee by default
  // The coder: tangential detail components' quantizer step relative to
  // normal ones (0.25 .. 64); bits per coordinate of the base mesh's grid
  // (4 .. 24); bit planes stored as raw bits, which decode faster (0 .. 31;
  // 0 writes .srm version 1).
  double tangential_factor = 4.0;
  int base_bits = 10;
  int raw_planes = 2;
  // Called after each stage; may be empty.
  std::function<void(const EncodeProgress&)> progress;
};

// What encode() measured and chose.
struct EncodeReport {
  int levels = 0;
  uint64_t base_vertices = 0;
  uint64_t crease_edges = 0;       // base edges kept sharp (the remesh lays them along the input's creases)
  uint64_t bytes = 0;              // of the file returned
  uint64_t full_stream_bytes = 0;  // of the whole embedded stream
  uint64_t minimum_bytes = 0;      // the header, base mesh, creases and flags: the smallest file possible
  double psnr = 0;                 // of the file returned against the input, estimated by the encoder
  double seconds_remesh = 0, seconds_coding = 0, seconds_rate = 0;
};

// Encodes `mesh` (cleaned first, as read_mesh cleans). Errors say what was
// wrong with the mesh or the options, and what would work instead.
StatusOr<std::vector<uint8_t>> encode(const Mesh& mesh, const EncodeOptions& options = {},
                                      EncodeReport* report = nullptr);

}  // namespace srcodec
