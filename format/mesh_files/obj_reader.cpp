#include "format/mesh_files/obj_reader.h"

#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include "format/mesh_files/text_numbers.h"

namespace srcodec {
namespace {

constexpr auto kMaxIndex = static_cast<long long>(std::numeric_limits<int32_t>::max());

std::string_view trim_right(std::string_view s) {
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Logical lines of an OBJ file: physical lines joined where one ends with a
// backslash, each with the number of its first physical line.
class ObjLines {
 public:
  explicit ObjLines(const std::string& bytes) : bytes_(bytes) {}

  bool next(std::string_view* line, size_t* number) {
    if (pos_ >= bytes_.size()) return false;
    std::string_view text = physical();
    *number = line_;
    std::string_view trimmed = trim_right(text);
    if (trimmed.empty() || trimmed.back() != '\\') {
      *line = text;
      return true;
    }
    joined_.clear();
    for (;;) {
      trimmed.remove_suffix(1);  // the backslash
      joined_.append(trimmed.data(), trimmed.size());
      joined_ += ' ';
      if (pos_ >= bytes_.size()) break;
      text = physical();
      trimmed = trim_right(text);
      if (trimmed.empty() || trimmed.back() != '\\') {
        joined_.append(text.data(), text.size());
        break;
      }
    }
    *line = joined_;
    return true;
  }

 private:
  std::string_view physical() {
    size_t end = bytes_.find('\n', pos_);
    if (end == std::string::npos) end = bytes_.size();
    std::string_view text(bytes_.data() + pos_, end - pos_);
    pos_ = end + 1;
    ++line_;
    return text;
  }

  const std::string& bytes_;
  size_t pos_ = 0;
  size_t line_ = 0;
  std::string joined_;
};

std::string quoted(std::string_view word) { return "'" + std::string(word) + "'"; }

}  // namespace

Status read_obj(const std::string& bytes, PolygonMesh* mesh) {
  ObjLines lines(bytes);
  std::string_view line;
  size_t number = 0;
  std::vector<std::string_view> words;
  std::vector<int32_t> face;
  std::vector<size_t> face_lines;  // for errors about indices past the last vertex
  while (lines.next(&line, &number)) {
    split_words(line.substr(0, line.find('#')), &words);
    if (words.empty()) continue;
    if (words[0] == "v") {
      if (words.size() < 4) {
        return line_error(number, "'v' line has " + std::to_string(words.size() - 1) + " coordinates, needs 3");
      }
      Eigen::Vector3d p;
      for (int k = 0; k < 3; ++k) {
        if (!parse_finite(words[1 + k], &p[k]))
          return line_error(number, "coordinate " + quoted(words[1 + k]) + " is not a finite number");
      }
      if (static_cast<long long>(mesh->positions.size()) >= kMaxIndex)
        return line_error(number, "more than " + std::to_string(kMaxIndex) + " vertices");
      mesh->positions.push_back(p);
    } else if (words[0] == "f" || words[0] == "fo") {
      face.clear();
      for (size_t k = 1; k < words.size(); ++k) {
        const std::string_view corner = words[k];
        const std::string_view vertex = corner.substr(0, corner.find('/'));
        long long index = 0;
        if (!parse_integer(vertex, &index))
          return line_error(number, "face corner " + quoted(corner) + " does not start with a vertex index");
        const auto count = static_cast<long long>(mesh->positions.size());
        if (index == 0) return line_error(number, "face uses vertex index 0 (OBJ counts from 1)");
        if (index < 0) {
          if (index < -count) {  // (-index would overflow for the most negative value)
            return line_error(number, "face uses relative vertex index " + std::to_string(index) + " but only " +
                                          std::to_string(count) + " vertices come before it");
          }
          index += count;
        } else {
          if (index > kMaxIndex)
            return line_error(number, "face uses vertex index " + std::to_string(index) + ", beyond any mesh");
          index -= 1;
        }
        face.push_back(static_cast<int32_t>(index));
      }
      if (face.size() < 3) {
        return line_error(number, "face has " + std::to_string(face.size()) + " corners, needs at least 3");
      }
      if (mesh->corners.size() + face.size() > static_cast<size_t>(kMaxIndex))
        return line_error(number, "more than " + std::to_string(kMaxIndex) + " face corners");
      mesh->add_face(face.data(), static_cast<int32_t>(face.size()));
      face_lines.push_back(number);
    }
    // Every other statement (vt, vn, vp, g, o, s, usemtl, mtllib, l, p,
    // curves) carries nothing srcodec codes.
  }
  // Positive indices may in principle point forward, so they are checked
  // once every vertex is known.
  const auto count = static_cast<int32_t>(mesh->positions.size());
  for (size_t f = 0; f < mesh->num_faces(); ++f) {
    for (int32_t k = 0; k < mesh->face_size(f); ++k) {
      const int32_t v = mesh->face(f)[k];
      if (v >= count) {
        return line_error(face_lines[f], "face uses vertex index " + std::to_string(int64_t{v} + 1) +
                                             " but the file has " + std::to_string(count) + " vertices");
      }
    }
  }
  return ok_status();
}

}  // namespace srcodec
