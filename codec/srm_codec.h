// The whole codec between a semi-regular mesh and .srm bytes (DESIGN.md data
// flow): base mesh coding, refinement flags, the lifted Butterfly transform,
// dead-zone quantization scaled per level and component, and embedded
// bit-plane coding, in the container of format/srm/srm_file.h.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "format/mesh.h"
#include "format/srm/srm_file.h"
#include "format/status.h"
#include "format/semi_regular/semi_regular_mesh.h"

namespace srcodec {

struct SrmEncodeOptions {
  // The finest quantizer step of the full stream, as a fraction of the input's
  // bounding-box diagonal: far below any remeshing error, since rate control
  // truncates the embedded stream rather than re-quantizing.
  double step_fraction = 1.0 / 65536.0;
  // Tangential detail components move vertices along the surface, which
  // changes the surface distance little, so they get a coarser step.
  double tangential_factor = 4.0;
  // Base positions are coded on a grid of this many bits per coordinate; the
  // embedded stream refines them further (the base residual, level f = 0).
  int base_bits = 10;
  // The symbols of this many lowest bit planes are written as raw bits, not
  // arithmetic-coded (.srm version 2 or 3, codec/bitplane_model.h): they are close to
  // even there, and raw bits decode several times faster. 0: none (version 1
  // when the mesh has no creases).
  // (What two planes cost and save: docs/codec_design.md.)
  int raw_planes = 2;
};

struct EncodedSrm {
  std::vector<uint8_t> bytes;  // the full file
  SrmHeader header;
  uint64_t header_size = 0;
};

// `input` is the original (cleaned) mesh: its counts and bounding box go in
// the header, for bits per vertex and PSNR.
StatusOr<EncodedSrm> encode_srm(const SemiRegularMesh& mesh, const TriangleMesh& input,
                                const SrmEncodeOptions& options = {});

struct SrmDecodeOptions {
  int level = -1;                          // -1: the finest the file has
  // Refuse files that would decode to more vertices (about 500 bytes of
  // decoder memory each): a tiny file can describe a huge uniform mesh.
  uint64_t max_vertices = uint64_t{1} << 22;
  // False: decode on the calling thread only. True: big files use a second
  // core (coefficients, wavelet plan, lifting and page mapping side by side).
  // The mesh is the same either way, bit for bit.
  bool threads = true;
};

struct DecodedSrm {
  TriangleMesh mesh;
  int level = 0;             // the level decoded (lower than asked when the file was cut in the flags)
  int last_plane = -1;       // the lowest bit plane decoded completely, -1: none
  uint64_t bytes_used = 0;   // the file's bytes that went into the mesh
  size_t base_vertices = 0;
  // The file ends inside its base mesh: `mesh` holds the base triangles
  // decoded before the cut (maybe none) and level is 0.
  bool base_cut = false;
  // The edges of `mesh` along which the surface is sharp, (a, b) with a <
  // b, sorted: the file's base creases (SemiRegularMesh::crease_edges
  // renumbered as the base mesh coder numbers vertices) refined to `level`
  // (crease_edges_up_to). Empty in a file without creases (versions 1 and 2).
  std::vector<std::array<int32_t, 2>> crease_edges;
  // The file ends inside its crease chunk: `mesh` is the whole base mesh at
  // level 0 (no level above can be decoded without the creases) and
  // crease_edges is empty.
  bool creases_cut = false;
};

// Decodes what `file` holds: a prefix decodes to the best mesh its bytes
// allow (cut inside the base mesh: the base triangles before the cut; inside
// the creases: the base mesh); a failed checksum is an error.
StatusOr<DecodedSrm> decode_srm(const SrmFile& file, const SrmDecodeOptions& options = {});

// The crease edges of the file's base mesh (none for a file without
// creases), as decode_srm reads them: the base mesh and crease chunks must be
// whole and pass their checksums.
StatusOr<std::vector<std::array<int32_t, 2>>> decode_srm_creases(const SrmFile& file);

}  // namespace srcodec
