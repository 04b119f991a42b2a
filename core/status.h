// Error values for untrusted input. Programmer errors assert; bad files, bad
// thresholds and bad command lines come back as a Status carrying a message of
// the form "path:line: what is wrong".
#pragma once

#include <string>
#include <utility>

namespace tetlod {

class [[nodiscard]] Status {
 public:
  Status() = default;  // ok
  static Status ok_status() { return Status(); }
  static Status error(std::string message) {
    Status s;
    s.ok_ = false;
    s.message_ = std::move(message);
    return s;
  }
  // An error in a value given (a threshold; a size too small for this mesh), not in
  // a file: the command line's usage error (exit code 2), not bad input.
  static Status bad_value(std::string message) {
    Status s = error(std::move(message));
    s.bad_value_ = true;
    return s;
  }

  bool ok() const { return ok_; }
  bool bad_value() const { return bad_value_; }
  explicit operator bool() const { return ok_; }
  // Empty when ok().
  const std::string& message() const { return message_; }

 private:
  bool ok_ = true;
  bool bad_value_ = false;
  std::string message_;
};

}  // namespace tetlod
