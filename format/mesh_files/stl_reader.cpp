#include "format/mesh_files/stl_reader.h"

#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "format/mesh_files/text_numbers.h"

namespace srcodec {
namespace {

constexpr size_t kBinaryHeader = 84;    // 80-byte comment + uint32 count
constexpr size_t kBinaryTriangle = 50;  // normal, 3 corners, attribute word

// Gives each distinct corner position one vertex index.
class CornerWelder {
 public:
  explicit CornerWelder(PolygonMesh* mesh) : mesh_(mesh) {}

  int32_t index(const Eigen::Vector3d& p) {
    Key key;
    for (int k = 0; k < 3; ++k) key[k] = p[k] == 0.0 ? 0.0 : p[k];  // -0 and +0 are one point
    const auto [it, added] = index_.try_emplace(key, static_cast<int32_t>(mesh_->positions.size()));
    if (added) mesh_->positions.push_back(p);
    return it->second;
  }

 private:
  using Key = std::array<double, 3>;
  struct Hash {
    size_t operator()(const Key& k) const {
      uint64_t h = 0x9e3779b97f4a7c15ull;
      for (double d : k) {
        uint64_t bits;
        std::memcpy(&bits, &d, sizeof bits);
        h = (h ^ bits) * 0xff51afd7ed558ccdull;
        h ^= h >> 32;
      }
      return static_cast<size_t>(h);
    }
  };
  PolygonMesh* mesh_;
  std::unordered_map<Key, int32_t, Hash> index_;
};

std::string lower(std::string_view word) {
  std::string out(word.substr(0, 16));
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

uint32_t binary_count(const std::string& bytes) {
  uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, sizeof count);  // little-endian, as x86 and ARM Linux
  return count;
}

bool is_binary(const std::string& bytes) {
  return bytes.size() >= kBinaryHeader &&
         bytes.size() - kBinaryHeader == uint64_t{binary_count(bytes)} * kBinaryTriangle;
}

Status read_binary(const std::string& bytes, PolygonMesh* mesh) {
  const uint32_t count = binary_count(bytes);
  CornerWelder welder(mesh);
  mesh->face_offsets.reserve(size_t{count} + 1);
  mesh->corners.reserve(size_t{count} * 3);
  for (uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + kBinaryHeader + size_t{t} * kBinaryTriangle;
    int32_t face[3];
    for (int c = 0; c < 3; ++c) {
      float xyz[3];
      std::memcpy(xyz, record + 12 * (c + 1), sizeof xyz);
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
        return parse_error("triangle " + std::to_string(t + 1) + " has a corner that is not a finite number");
      }
      face[c] = welder.index(Eigen::Vector3d(xyz[0], xyz[1], xyz[2]));
    }
    mesh->add_face(face, 3);
  }
  return ok_status();
}

Status read_ascii(const std::string& bytes, PolygonMesh* mesh) {
  CornerWelder welder(mesh);
  std::vector<std::string_view> words;
  std::vector<int32_t> loop;
  bool in_loop = false;
  size_t pos = 0;
  for (size_t line = 1; pos < bytes.size(); ++line) {
    size_t end = bytes.find('\n', pos);
    if (end == std::string::npos) end = bytes.size();
    split_words(std::string_view(bytes.data() + pos, end - pos), &words);
    pos = end + 1;
    if (words.empty()) continue;
    const std::string keyword = lower(words[0]);  // some exporters write FACET, VERTEX, ...
    if (keyword == "vertex") {
      if (!in_loop) return line_error(line, "'vertex' outside an 'outer loop'");
      if (words.size() < 4) return line_error(line, "'vertex' needs 3 coordinates");
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        if (!parse_finite(words[1 + k], &p[k]))
          return line_error(line, "coordinate '" + std::string(words[1 + k]) + "' is not a finite number");
      }
      loop.push_back(welder.index(p));
    } else if (keyword == "outer") {
      if (in_loop) return line_error(line, "'outer loop' inside another loop");
      in_loop = true;
      loop.clear();
    } else if (keyword == "endloop") {
      if (!in_loop) return line_error(line, "'endloop' without an 'outer loop'");
      if (loop.size() < 3) return line_error(line, "facet has " + std::to_string(loop.size()) + " vertices, needs 3");
      mesh->add_face(loop.data(), static_cast<int32_t>(loop.size()));
      in_loop = false;
    } else if (keyword == "solid" || keyword == "endsolid" || keyword == "facet" || keyword == "endfacet") {
      if (in_loop) return line_error(line, "'" + keyword + "' before 'endloop'");
    } else {
      return line_error(line, "unexpected '" + std::string(words[0].substr(0, 40)) + "' in an ascii STL file");
    }
  }
  if (in_loop) return parse_error("the file ends inside a facet (no 'endloop')");
  return ok_status();
}

}  // namespace

Status read_stl(const std::string& bytes, PolygonMesh* mesh) {
  if (is_binary(bytes)) return read_binary(bytes, mesh);
  std::vector<std::string_view> first;
  split_words(std::string_view(bytes).substr(0, bytes.find('\n')), &first);
  const bool has_nul = bytes.find('\0') != std::string::npos;
  if (!first.empty() && lower(first[0]) == "solid" && (!has_nul || bytes.size() < kBinaryHeader)) {
    return read_ascii(bytes, mesh);
  }
  if (bytes.size() < kBinaryHeader) {
    return parse_error("not an STL file: " + std::to_string(bytes.size()) +
                       " bytes, shorter than a binary STL header, and no 'solid' line");
  }
  const uint64_t needed = kBinaryHeader + uint64_t{binary_count(bytes)} * kBinaryTriangle;
  return parse_error("binary STL says " + std::to_string(binary_count(bytes)) + " triangles, which take " +
                     std::to_string(needed) + " bytes, but the file has " + std::to_string(bytes.size()));
}

}  // namespace srcodec
