#pragma once
// The value read from a user's text, or the message saying why the text is wrong. The subset of
// std::expected<T, std::string> that the text readers of core need. It dates from when the fuzz
// build was clang 14, which could not compile <expected>; the clang-19 fuzz build (Makefile
// fuzz-build) can, so std::expected would now do here too.
#include <string>
#include <utility>

namespace virtcom {

template <class T>
class TextResult {
 public:
  TextResult(T value) : value_(std::move(value)), ok_(true) {}  // NOLINT: implicit, as std::expected
  static TextResult failure(std::string message) { return TextResult(std::move(message), Failure{}); }

  explicit operator bool() const { return ok_; }
  bool has_value() const { return ok_; }
  // The value (a default T without one) and the message (empty without one).
  const T& operator*() const { return value_; }
  const T* operator->() const { return &value_; }
  const std::string& error() const { return error_; }
  friend bool operator==(const TextResult& r, const T& v) { return r.ok_ && r.value_ == v; }

 private:
  struct Failure {};
  TextResult(std::string message, Failure) : error_(std::move(message)) {}
  T value_{};
  std::string error_;
  bool ok_ = false;
};

}  // namespace virtcom
