// How much memory a remesh will need, estimated before it starts, against
// what the machine can give: a mesh beyond it is refused up front, with the
// estimate and what would fit, instead of ending in an out-of-memory kill.
#pragma once

#include <cstdint>
#include <string>

namespace srcodec {

// Peak resident memory of an encode per oversampled vertex: every remesh
// stage works on the oversampled mesh, and docs/encoder_profile.md measured
// 390 to 570 bytes per oversampled vertex from 0.5M to 8.6M of them; the
// upper end with a margin.
inline constexpr double kRemeshBytesPerVertex = 640.0;

// The vertices `steps` rounds of 1-to-4 subdivision give a mesh of
// `vertices` and `triangles` (each round adds a vertex per edge).
uint64_t subdivided_vertices(uint64_t vertices, uint64_t triangles, int steps);

uint64_t remesh_memory_estimate(uint64_t oversampled_vertices);

// The memory this process can still take: /proc/meminfo's MemAvailable on
// Linux, else the free physical pages; 0 when neither is known.
uint64_t available_memory();

// "3.4 GB" or "640 MB": a byte count for messages.
std::string memory_text(uint64_t bytes);

}  // namespace srcodec
