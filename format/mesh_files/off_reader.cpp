#include "format/mesh_files/off_reader.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace srcodec {
namespace {

// Non-empty lines with comments removed, each with its 1-based line number.
struct Line {
  size_t number;
  std::vector<std::string> words;
};

std::vector<Line> content_lines(const std::string& bytes) {
  std::vector<Line> lines;
  std::istringstream in(bytes);
  std::string text;
  for (size_t n = 1; std::getline(in, text); ++n) {
    std::istringstream words(text.substr(0, text.find('#')));
    Line line{n, {}};
    for (std::string w; words >> w;) line.words.push_back(w);
    if (!line.words.empty()) lines.push_back(std::move(line));
  }
  return lines;
}

Status at(const Line& line, const std::string& what) {
  return parse_error("line " + std::to_string(line.number) + ": " + what);
}

// The whole word is one finite number.
bool to_finite(const std::string& word, double* out) {
  const char* begin = word.c_str();
  char* end = nullptr;
  *out = std::strtod(begin, &end);
  return end != begin && *end == '\0' && std::isfinite(*out);
}

bool to_int(const std::string& word, long long* out) {
  std::istringstream in(word);
  return (in >> *out) && in.peek() == EOF;
}

}  // namespace

Status read_off(const std::string& bytes, PolygonMesh* mesh) {
  const std::vector<Line> lines = content_lines(bytes);
  if (lines.empty() || lines[0].words[0].find("OFF") == std::string::npos)
    return parse_error("not an OFF file (no OFF keyword on the first line)");
  if (lines[0].words.size() > 1 && lines[0].words[1] == "BINARY") return unsupported("binary OFF is not supported");

  // The counts follow the keyword, on its line or the next.
  size_t next = 0;
  std::vector<std::string> counts(lines[0].words.begin() + 1, lines[0].words.end());
  if (counts.empty()) {
    if (lines.size() < 2) return parse_error("OFF file ends before its vertex and face counts");
    counts = lines[1].words;
    next = 2;
  } else {
    next = 1;
  }
  const Line& count_line = lines[next - 1];
  long long nv = 0, nf = 0;
  if (counts.size() < 2 || !to_int(counts[0], &nv) || !to_int(counts[1], &nf) || nv < 0 || nf < 0)
    return at(count_line, "expected vertex and face counts");
  const auto available = static_cast<long long>(lines.size() - next);
  if (nv > available || nf > available - nv) {
    return at(count_line, "counts say " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                              " faces but only " + std::to_string(available) + " lines follow");
  }

  mesh->positions.reserve(static_cast<size_t>(nv));
  for (long long v = 0; v < nv; ++v) {
    const Line& line = lines[next++];
    if (line.words.size() < 3) return at(line, "vertex needs 3 coordinates");
    Eigen::Vector3d p;
    for (int k = 0; k < 3; ++k) {
      if (!to_finite(line.words[k], &p[k])) return at(line, "'" + line.words[k] + "' is not a finite number");
    }
    mesh->positions.push_back(p);
  }
  std::vector<int32_t> face;
  for (long long f = 0; f < nf; ++f) {
    const Line& line = lines[next++];
    long long n = 0;
    if (!to_int(line.words[0], &n) || n < 1 || n > static_cast<long long>(line.words.size()) - 1)
      return at(line, "face corner count '" + line.words[0] + "' does not match the indices on the line");
    face.clear();
    for (long long k = 1; k <= n; ++k) {
      long long index = 0;
      if (!to_int(line.words[k], &index)) return at(line, "face index '" + line.words[k] + "' is not an integer");
      if (index < 0 || index >= nv)
        return at(line, "face uses vertex index " + line.words[k] + " but the file has " + std::to_string(nv) + " vertices");
      face.push_back(static_cast<int32_t>(index));
    }
    mesh->add_face(face.data(), static_cast<int32_t>(face.size()));
  }
  return ok_status();
}

}  // namespace srcodec
