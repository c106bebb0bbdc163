// Status and StatusOr: every path that reads bytes or user input returns one,
// and the message carries what went wrong and where (file, offset, element).
#pragma once

#include <optional>
#include <string>
#include <utility>

namespace srcodec {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,  // a user option or parameter is out of range
  kNotFound,         // a file does not exist
  kIoError,          // the OS refused a read or write
  kParseError,       // the bytes are not a valid file of their format
  kInvalidMesh,      // a readable mesh that srcodec cannot work with
  kUnsupported,      // a valid feature srcodec does not handle (yet)
  kInternal,         // a bug: an invariant did not hold
};

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

  // "context: message", for adding the file name or stage on the way up.
  Status with_context(const std::string& context) const {
    if (ok()) return *this;
    return Status(code_, context + ": " + message_);
  }

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status ok_status() { return Status(); }
inline Status invalid_argument(std::string m) { return {StatusCode::kInvalidArgument, std::move(m)}; }
inline Status not_found(std::string m) { return {StatusCode::kNotFound, std::move(m)}; }
inline Status io_error(std::string m) { return {StatusCode::kIoError, std::move(m)}; }
inline Status parse_error(std::string m) { return {StatusCode::kParseError, std::move(m)}; }
inline Status invalid_mesh(std::string m) { return {StatusCode::kInvalidMesh, std::move(m)}; }
inline Status unsupported(std::string m) { return {StatusCode::kUnsupported, std::move(m)}; }
inline Status internal_error(std::string m) { return {StatusCode::kInternal, std::move(m)}; }

// A value or the Status that explains why there is none.
template <typename T>
class [[nodiscard]] StatusOr {
 public:
  StatusOr(Status status) : status_(std::move(status)) {}  // NOLINT: implicit by design
  StatusOr(T value) : value_(std::move(value)) {}          // NOLINT: implicit by design

  bool ok() const { return status_.ok(); }
  const Status& status() const { return status_; }
  T& value() & { return *value_; }
  const T& value() const& { return *value_; }
  T&& value() && { return std::move(*value_); }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }

 private:
  Status status_;
  std::optional<T> value_;
};

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
