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

  bool ok() const { return ok_; }
  explicit operator bool() const { return ok_; }
  // Empty when ok().
  const std::string& message() const { return message_; }

 private:
  bool ok_ = true;
  std::string message_;
};

}  // namespace tetlod
