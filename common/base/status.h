// Status and Result: errors as values at module boundaries.
//
// Every fallible function of common/ returns a Status or a Result<T>; no
// exception crosses a module. A Status carries a code and a message meant
// for people ("genome.json: elements[3].sign: must be +1 or -1, got 0").
// Both types are cheap to move and are not thread-safe to mutate
// concurrently (like any value type).
#ifndef ANIMAT_COMMON_BASE_STATUS_H_
#define ANIMAT_COMMON_BASE_STATUS_H_

#include <cassert>
#include <optional>
#include <string>
#include <utility>

namespace animat {

enum class StatusCode {
  kOk = 0,
  kInvalidArgument,  // Bad input: malformed file, out-of-range value.
  kNotFound,         // A named file or record does not exist.
  kIoError,          // Reading or writing failed.
  kInternal,         // A broken invariant of this program.
};

class [[nodiscard]] Status {
 public:
  Status() = default;  // OK.

  static Status Ok() { return Status(); }
  static Status InvalidArgument(std::string message) {
    return Status(StatusCode::kInvalidArgument, std::move(message));
  }
  static Status NotFound(std::string message) {
    return Status(StatusCode::kNotFound, std::move(message));
  }
  static Status IoError(std::string message) {
    return Status(StatusCode::kIoError, std::move(message));
  }
  static Status Internal(std::string message) {
    return Status(StatusCode::kInternal, std::move(message));
  }

  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }

  // Returns a copy whose message is "prefix: message" (for adding the
  // file name or field path as an error travels outwards).
  Status WithPrefix(const std::string& prefix) const {
    if (ok()) return *this;
    return Status(code_, prefix + ": " + message_);
  }

  // "OK" or "<code name>: <message>".
  std::string ToString() const;

 private:
  Status(StatusCode code, std::string message)
      : code_(code), message_(std::move(message)) {}

  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

// A value of type T or the Status saying why there is none.
template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit by design
  Result(Status status) : status_(std::move(status)) {  // NOLINT
    assert(!status_.ok() && "a Result without a value needs an error");
    if (status_.ok()) status_ = Status::Internal("Result built from OK");
  }

  bool ok() const { return value_.has_value(); }
  const Status& status() const { return status_; }

  // Preconditions: ok().
  const T& value() const& {
    assert(ok());
    return *value_;
  }
  T& value() & {
    assert(ok());
    return *value_;
  }
  T&& value() && {
    assert(ok());
    return std::move(*value_);
  }
  const T& operator*() const& { return value(); }
  T& operator*() & { return value(); }
  const T* operator->() const { return &value(); }
  T* operator->() { return &value(); }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace animat

#endif  // ANIMAT_COMMON_BASE_STATUS_H_
