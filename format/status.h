// Status and StatusOr (the public <srcodec/status.h>) with the library's
// shorthands: a constructor per code, and macros that return on an error.
#pragma once

#include <srcodec/status.h>

#include <cstdio>
#include <string>
#include <utility>

namespace srcodec {

inline Status ok_status() { return Status(); }
inline Status invalid_argument(std::string m) { return {StatusCode::kInvalidArgument, std::move(m)}; }
inline Status not_found(std::string m) { return {StatusCode::kNotFound, std::move(m)}; }
inline Status io_error(std::string m) { return {StatusCode::kIoError, std::move(m)}; }
inline Status parse_error(std::string m) { return {StatusCode::kParseError, std::move(m)}; }
inline Status invalid_mesh(std::string m) { return {StatusCode::kInvalidMesh, std::move(m)}; }
inline Status unsupported(std::string m) { return {StatusCode::kUnsupported, std::move(m)}; }
inline Status internal_error(std::string m) { return {StatusCode::kInternal, std::move(m)}; }

// A number as the messages write it: %g, short, no trailing zeros.
inline std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

}  // namespace srcodec

#define SRCODEC_CONCAT_INNER(a, b) a##b
#define SRCODEC_CONCAT(a, b) SRCODEC_CONCAT_INNER(a, b)

#define SRCODEC_RETURN_IF_ERROR(expr)              \
  do {                                             \
    ::srcodec::Status srcodec_status_ = (expr);    \
    if (!srcodec_status_.ok()) return srcodec_status_; \
  } while (0)

#define SRCODEC_ASSIGN_OR_RETURN_IMPL(tmp, lhs, expr) \
  auto tmp = (expr);                                  \
  if (!tmp.ok()) return tmp.status();                 \
  lhs = std::move(tmp).value()

#define SRCODEC_ASSIGN_OR_RETURN(lhs, expr) \
  SRCODEC_ASSIGN_OR_RETURN_IMPL(SRCODEC_CONCAT(srcodec_statusor_, __LINE__), lhs, expr)
