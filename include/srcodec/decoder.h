// Decoding .srm files: any level, from any prefix of the bytes. Part of
// srcodec::decoder, which needs nothing but a C++17 standard library.
//
// Safe on untrusted input: every call checks counts against each other and
// against `max_vertices` before it allocates, verifies the checksums of what
// it uses, and answers bad bytes with a Status whose message names the chunk
// and byte offset. Nothing throws or aborts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <srcodec/mesh.h>
#include <srcodec/status.h>

namespace srcodec {

struct DecodeOptions {
  // The level to decode: 0 is the base mesh, -1 the finest the file has. A
  // level above the file's finest is an error. When the bytes end inside the
  // refinement flags of a level at or below it, the finest level they
  // complete is decoded instead (Decoded::level says which).
  int level = -1;
  // Decode only the first `max_bytes` bytes, as if the file had been cut
  // there (0, or more than there are: all of them).
  uint64_t max_bytes = 0;
  // Refuse, before allocating, a file whose chosen level has more vertices
  // than this (about 500 bytes of memory each while decoding): a file of a
  // few hundred bytes can describe a mesh of millions. 1 .. 2^31.
  uint64_t max_vertices = uint64_t{1} << 22;
  // Use a second thread for large meshes. The mesh is the same, bit for bit.
  bool threads = true;
};

struct Decoded {
  Mesh mesh;
  int level = 0;            // the level decoded
  uint64_t bytes_used = 0;  // how many of the bytes went into the mesh
  // The lowest bit plane of the coefficients decoded completely, -1: none
  // (the bytes end before every coefficient's top plane).
  int last_complete_plane = -1;
  // The bytes end inside the base mesh: `mesh` holds the base triangles
  // decoded before the cut (maybe none), at level 0.
  bool base_cut = false;
  // The edges of `mesh` along which the surface is sharp (the encoder's
  // creases, at `level`: a base edge the finer levels split gives its
  // halves): two vertex ids of `mesh` per edge, the smaller first, sorted.
  // corner_normals (<srcodec/mesh.h>) shades the mesh with them sharp. Empty
  // for a file without creases. (FileInfo::crease_edges counts the base
  // mesh's, which are these at level 0.)
  std::vector<uint32_t> crease_edges;
  // The bytes end inside the creases: `mesh` is the base mesh (level 0) and
  // crease_edges is empty.
  bool creases_cut = false;
};

// Decodes `size` bytes at `data` (a whole .srm file or a prefix of one).
StatusOr<Decoded> decode(const uint8_t* data, size_t size, const DecodeOptions& options = {});

// What `srcodec info FILE.srm` prints: the header, and where the bytes go.
struct FileInfo {
  int version = 0;
  uint64_t file_bytes = 0;      // present
  uint64_t declared_bytes = 0;  // of the whole file; more than file_bytes for a prefix
  uint64_t header_bytes = 0;
  uint64_t input_vertices = 0, input_triangles = 0;  // of the mesh that was encoded
  double bbox_min[3] = {0, 0, 0}, bbox_max[3] = {0, 0, 0};  // of that mesh
  double bits_per_vertex = 0;   // 8 file_bytes / input_vertices
  uint64_t base_vertices = 0, base_triangles = 0, base_bytes = 0;
  // The creases (format version 3): the chunk's bytes (0: a file without
  // creases) and how many base edges it marks (a decoded level's
  // Decoded::crease_edges refine them); -1 when that is not known
  // (the bytes end before the base mesh and creases are whole, or they do
  // not decode).
  uint64_t crease_bytes = 0;
  int64_t crease_edges = 0;
  int base_bits = 0;            // base positions' grid, bits per coordinate
  int levels = 0;               // the finest level
  double quantizer_step = 0;
  int top_plane = -1;           // the coefficients' bit planes are top_plane .. 0; -1: all zero
  int raw_planes = 0;           // planes below this are stored as raw bits
  struct Level {
    uint64_t vertices = 0;           // of the mesh of this level
    uint64_t flag_bytes = 0;         // the refinement flags that make it from the level below
    uint64_t coefficient_bytes = 0;  // its wavelet coefficients, all planes
    // The shortest prefix that decodes to this level (header, base mesh and
    // the flags up to it; the coefficients then refine it as more arrives).
    uint64_t drawable_from = 0;
  };
  std::vector<Level> level_info;  // levels + 1 entries
  struct Plane {
    int plane = 0;
    uint64_t bytes = 0;  // of every level
    uint64_t end = 0;    // the prefix that holds this plane of every level completely
  };
  std::vector<Plane> planes;  // top_plane down to 0, as the file orders them
};

// Reads the header of `size` bytes at `data` (a file or a prefix that holds
// its header).
StatusOr<FileInfo> inspect(const uint8_t* data, size_t size);

// A smaller valid file: at most `bytes` bytes, keeping as many of the
// coefficients' bytes as fit (what `srcodec encode --bytes N` writes). It
// decodes like the prefix of the same length, and, unlike a plain prefix,
// its checksums are whole. An error when `bytes` cannot hold the header,
// base mesh, creases and refinement flags (the message says how many that
// takes).
StatusOr<std::vector<uint8_t>> truncate(const uint8_t* data, size_t size, uint64_t bytes);

}  // namespace srcodec
