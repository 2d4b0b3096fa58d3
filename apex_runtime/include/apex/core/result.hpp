// Errors as values: what graph edits, parameter changes and file loading
// return. Exceptions stay for programming errors (see docs/architecture.md).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

namespace apex {

/** @brief Success, or failure with a message that names what was wrong. */
class [[nodiscard]] Status {
 public:
  static Status ok() { return Status(); }
  static Status error(std::string message) { return Status(std::move(message)); }

  bool isOk() const { return !message_.has_value(); }
  explicit operator bool() const { return isOk(); }
  /** @brief The failure's message; empty on success. */
  const std::string& message() const {
    static const std::string kEmpty;
    return message_ ? *message_ : kEmpty;
  }

 private:
  Status() = default;
  explicit Status(std::string m) : message_(std::move(m)) {}
  std::optional<std::string> message_;
};

/** @brief A value, or the message of why there is none (C++17 has no std::expected). */
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit on purpose
  Result(Status failure) : error_(failure.message()) {  // NOLINT
    if (failure.isOk()) throw std::logic_error("Result built from a successful Status without a value");
  }

  bool isOk() const { return value_.has_value(); }
  explicit operator bool() const { return isOk(); }
  const std::string& message() const { return error_; }
  Status status() const { return isOk() ? Status::ok() : Status::error(error_); }

  /** @brief The value; throws std::logic_error when there is none (a programming error). */
  const T& value() const& {
    if (!value_) throw std::logic_error("Result has no value: " + error_);
    return *value_;
  }
  T& value() & {
    if (!value_) throw std::logic_error("Result has no value: " + error_);
    return *value_;
  }
  T&& value() && {
    if (!value_) throw std::logic_error("Result has no value: " + error_);
    return std::move(*value_);
  }
  const T* operator->() const { return &value(); }
  const T& operator*() const { return value(); }

 private:
  std::optional<T> value_;
  std::string error_;
};

}  // namespace apex
