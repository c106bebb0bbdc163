#include "format/text_numbers.h"

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace srcodec {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// The whole token is one finite number.
bool is_finite_number(const std::string& token) {
  const char* begin = token.c_str();
  char* end = nullptr;
  const double v = std::strtod(begin, &end);
  return end != begin && *end == '\0' && std::isfinite(v);
}

Status line_error(size_t line, const std::string& what) {
  return parse_error("line " + std::to_string(line) + ": " + what);
}

// Checks `count` coordinates after the keyword of every line that starts with it.
Status check_keyword_lines(const std::string& bytes, const std::string& keyword, size_t count) {
  std::istringstream in(bytes);
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    const auto words = split(line);
    if (words.empty() || words[0] != keyword) continue;
    if (words.size() < count + 1)
      return line_error(n, "'" + keyword + "' line has " + std::to_string(words.size() - 1) + " coordinates, needs " +
                               std::to_string(count));
    for (size_t k = 1; k <= count; ++k) {
      if (!is_finite_number(words[k]))
        return line_error(n, "coordinate '" + words[k] + "' is not a finite number (NaN or infinite?)");
    }
  }
  return ok_status();
}

// Every token after the header (comments aside) must be a finite number.
Status check_numeric_body(const std::string& bytes, size_t header_lines) {
  std::istringstream in(bytes);
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (n <= header_lines) continue;
    const auto hash = line.find('#');
    for (const auto& word : split(line.substr(0, hash))) {
      if (!is_finite_number(word)) return line_error(n, "'" + word + "' is not a finite number");
    }
  }
  return ok_status();
}

}  // namespace

Status check_text_numbers(const std::string& bytes, const std::string& ext) {
  if (ext == ".obj") return check_keyword_lines(bytes, "v", 3);
  if (ext == ".stl") {
    // Binary STL has an 80-byte header that may also start with "solid".
    if (bytes.rfind("solid", 0) != 0 || bytes.find("facet") == std::string::npos) return ok_status();
    return check_keyword_lines(bytes, "vertex", 3);
  }
  if (ext == ".ply") {
    const size_t end = bytes.find("end_header");
    if (end == std::string::npos || bytes.find("format ascii") > end) return ok_status();
    size_t header_lines = 1;
    for (size_t i = 0; i < end; ++i) header_lines += bytes[i] == '\n';
    return check_numeric_body(bytes, header_lines);
  }
  return ok_status();
}

}  // namespace srcodec
