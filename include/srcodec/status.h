// srcodec's error type. Every call that reads bytes, files or user options
// returns a Status or a StatusOr<T>; the message says what went wrong and
// where (file, byte offset, chunk, option). Nothing in the library throws or
// aborts on bad input.
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

// A value or the Status that explains why there is none. The value's
// accessors (value(), *, ->) may only be used when ok().
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
  T& operator*() & { return *value_; }
  const T& operator*() const& { return *value_; }
  T&& operator*() && { return std::move(*value_); }
  T* operator->() { return &*value_; }
  const T* operator->() const { return &*value_; }

 private:
  Status status_;
  std::optional<T> value_;
};

}  // namespace srcodec
