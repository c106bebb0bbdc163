// Words and numbers of text mesh files (OBJ, OFF, ascii PLY, ascii STL):
// every coordinate must be a finite number and every error names its line.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "format/status.h"

namespace srcodec {

// The whole of `word` is one finite decimal number ("1", "-2.5e3", "+.5");
// NaN, infinities, hexadecimal and trailing characters are refused.
bool parse_finite(std::string_view word, double* out);

// The whole of `word` is a decimal integer (a leading '+' or '-' allowed)
// that fits in 64 bits.
bool parse_integer(std::string_view word, long long* out);

// Splits `line` at spaces, tabs, carriage returns, vertical tabs and form
// feeds; `words` is cleared first.
void split_words(std::string_view line, std::vector<std::string_view>* words);

// "line N: what", the form of every text-parser error.
Status line_error(size_t line, const std::string& what);

// An ascii PLY's body, after its header, before it is parsed: our PLY reader
// would only say it ran out of numbers where a token is not a finite number.
// Binary PLY passes untouched.
Status check_ascii_ply_numbers(const std::string& bytes);

}  // namespace srcodec
