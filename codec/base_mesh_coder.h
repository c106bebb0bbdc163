// Compact coding of the base mesh (DESIGN.md codec/): connectivity by a
// cut-border traversal (Gumhold & Strasser 1998, "Real time compression of
// triangle mesh connectivity"; in the Edgebreaker / Touma-Gotsman family),
// positions on a uniform grid predicted across the traversal's gate edge
// (parallelogram rule, Touma & Gotsman 1998), all coded by an adaptive binary
// arithmetic coder. See base_mesh_model.h for the scheme and the stream.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "format/status.h"

namespace srcodec {

// A uniform grid: coordinate q maps to origin + step * q.
struct QuantizationGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // the input's bounding-box minimum
  double step = 1.0;                                  // > 0
  int bits = 12;  // coordinates are integers in [0, 2^bits - 1], bits 1..24
  Eigen::Vector3d dequantize(const Eigen::Vector3i& q) const;
  Eigen::Vector3i quantize(const Eigen::Vector3d& p) const;  // rounds and clamps into range
};

struct BaseMeshCode {
  std::vector<uint8_t> bytes;  // the coded base mesh
  // What the decoder will produce, so the encoder builds exactly the decoder's state:
  std::vector<std::array<int32_t, 3>> triangles;  // decoded order and corner rotation, new vertex ids
  std::vector<Eigen::Vector3d> positions;         // dequantized, per new vertex id
  std::vector<int32_t> new_to_old_vertex;         // new vertex id -> input vertex id
  std::vector<int32_t> new_to_old_triangle;       // decoded triangle -> input triangle (same cyclic orientation)
};

// Input: every index in range, no triangle repeats a vertex, each directed
// edge used at most once (manifold edges, consistent orientation), every
// vertex used. Boundaries, several components, any genus and vertices where
// several fans meet are all coded. Vertices and triangles are reordered and
// corners rotated (never flipped); the returned maps give the order chosen.
StatusOr<BaseMeshCode> encode_base_mesh(const std::vector<Eigen::Vector3d>& positions,
                                        const std::vector<std::array<int32_t, 3>>& triangles,
                                        const QuantizationGrid& grid);

struct DecodedBaseMesh {
  std::vector<std::array<int32_t, 3>> triangles;
  std::vector<Eigen::Vector3d> positions;
};

// Safe on untrusted bytes. `max_vertices`/`max_triangles`: limits from the
// file header; the decoder never holds more than they allow (storage grows
// only with what was actually decoded), and returns a clear error (what, and
// at which byte offset) on any inconsistency, trailing or missing bytes.
StatusOr<DecodedBaseMesh> decode_base_mesh(const uint8_t* data, size_t size, const QuantizationGrid& grid,
                                           size_t max_vertices, size_t max_triangles);

// The same for the first `size` bytes of a stream that may be longer (a file
// cut inside its base mesh): the triangles, with their vertices, decoded
// before the first symbol that depended on a missing byte (none while the
// counts at the start are incomplete). Errors as decode_base_mesh for what
// the present bytes get wrong.
StatusOr<DecodedBaseMesh> decode_base_mesh_prefix(const uint8_t* data, size_t size, const QuantizationGrid& grid,
                                                  size_t max_vertices, size_t max_triangles);

}  // namespace srcodec
