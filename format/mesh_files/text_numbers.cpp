#include "format/mesh_files/text_numbers.h"

#include <charconv>
#include <cmath>

namespace srcodec {

namespace {

// The whole of `word` is one number of type T, a leading '+' allowed.
template <typename T>
bool parse_whole(std::string_view word, T* out) {
  if (!word.empty() && word[0] == '+') word.remove_prefix(1);
  if (word.empty() || word[0] == '+') return false;
  const char* end = word.data() + word.size();
  const auto [ptr, ec] = std::from_chars(word.data(), end, *out);
  return ec == std::errc() && ptr == end;
}

}  // namespace

bool parse_finite(std::string_view word, double* out) { return parse_whole(word, out) && std::isfinite(*out); }

bool parse_integer(std::string_view word, long long* out) { return parse_whole(word, out); }

void split_words(std::string_view line, std::vector<std::string_view>* words) {
  words->clear();
  auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; };
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && space(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !space(line[i])) ++i;
    if (i > start) words->push_back(line.substr(start, i - start));
  }
}

Status line_error(size_t line, const std::string& what) {
  return parse_error("line " + std::to_string(line) + ": " + what);
}

Status check_ascii_ply_numbers(const std::string& bytes) {
  const size_t header_end = bytes.find("end_header");
  if (header_end == std::string::npos || bytes.find("format ascii") > header_end) return ok_status();
  std::vector<std::string_view> words;
  double value = 0;
  size_t line = 1, pos = 0;
  for (; pos < header_end; ++pos) line += bytes[pos] == '\n';
  pos = bytes.find('\n', header_end);
  while (pos != std::string::npos && pos < bytes.size()) {
    const size_t start = pos + 1;
    pos = bytes.find('\n', start);
    ++line;
    std::string_view text(bytes.data() + start, (pos == std::string::npos ? bytes.size() : pos) - start);
    split_words(text.substr(0, text.find('#')), &words);
    for (const auto word : words) {
      if (!parse_finite(word, &value)) return line_error(line, "'" + std::string(word) + "' is not a finite number");
    }
  }
  return ok_status();
}

}  // namespace srcodec
