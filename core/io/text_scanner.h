// A fast tokenizer for untrusted ASCII mesh files (internal to core/io).
//
// Tokens are runs of non-whitespace characters. The scanner keeps the 1-based line
// of the last token so that every error reads "name:line: message". Numbers are
// parsed with std::from_chars, without allocation. A failed read records the first
// error; the caller returns status() from there.
//
// Truncation: a number that ends exactly at the end of the text may have been cut
// short (the file "...12" cut to "...1" still parses), so by default such a number
// is an error. Sub-scanners over a delimited range (an XML element's content) turn
// this off with set_number_may_end_text(true).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/status.h"

namespace tetlod::io {

class TextScanner {
 public:
  // `name` (the path, for messages) must outlive the scanner. `comment` starts a
  // comment that runs to the end of the line when it begins a token; 0 for none.
  TextScanner(std::string_view text, const std::string& name, char comment = 0,
              size_t first_line = 1);

  void set_number_may_end_text(bool allowed) { number_may_end_text_ = allowed; }
  // From now on errors read "name: byte N: message", N the offset of the current
  // position from `base` (the start of the file): for files with binary sections,
  // where line numbers mean nothing.
  void report_byte_offsets(const char* base) { byte_base_ = base; }

  // The next token; false (without error) at the end of the text.
  bool next_token(std::string_view* token);
  // The next token without consuming it; false at the end of the text.
  bool peek_token(std::string_view* token);
  // True when only whitespace and comments remain.
  bool at_end();

  // Typed reads of the next token. `what` names the value in messages ("x
  // coordinate"). They fail on a missing token, trailing garbage, a non-finite
  // value or overflow.
  bool read_double(double* value, const char* what);
  bool read_int(int64_t* value, const char* what);
  // An integer in [min_value, max_value].
  bool read_int_in_range(int64_t* value, const char* what, int64_t min_value, int64_t max_value);
  // A number holding an integer ("3", "3.0", "3e0") in [min_value, max_value], for
  // ids that some writers store as floating point.
  bool read_integral(int64_t* value, const char* what, int64_t min_value, int64_t max_value);
  // A count of items that each take at least `min_bytes_per_item` bytes of the
  // remaining text, so that no caller reserves more than the text could hold; 0: a
  // count the caller bounds otherwise (a VTK data section's must equal the cells',
  // and may end the file with no array after it).
  bool read_count(uint64_t* count, const char* what, uint64_t min_bytes_per_item);
  // Skips `count` tokens that must look like numbers (keeps a wrong count from
  // silently swallowing the next section).
  bool skip_numbers(uint64_t count, const char* what);
  // Consumes the next token and checks it equals `keyword` (ASCII case-insensitive).
  bool expect_keyword(std::string_view keyword);

  // The rest of the current line (without the line break and trailing '\r'),
  // consuming the line break. Empty at the end of the text.
  std::string_view rest_of_line();

  // Raw access for structured formats (XML): the unread text, and a way to move
  // forward by `byte_count` bytes while counting line breaks.
  std::string_view remaining_text() const { return {pos_, size_t(end_ - pos_)}; }
  void advance(size_t byte_count);
  size_t remaining_bytes() const { return size_t(end_ - pos_); }

  // Line of the last token read (or of the current position after advance() and
  // rest_of_line()); at the end of the text it stays on the last token.
  size_t line() const { return token_line_; }
  size_t current_line() const { return line_; }
  const std::string& name() const { return name_; }

  // Records "name:line: message" (the first error wins) and returns false.
  bool fail(std::string_view message);
  bool fail_at_line(size_t line, std::string_view message);
  // Records the error of `other` (a scanner over part of this text) as this one's,
  // unless this one has failed already, and returns false.
  bool adopt_failure(const TextScanner& other);
  bool failed() const { return failed_; }
  Status status() const { return failed_ ? Status::error(error_) : Status(); }

  // True when the token starts like a number (digit, sign or '.'), not a keyword.
  static bool looks_numeric(std::string_view token);
  // True for ASCII case-insensitive equality.
  static bool equals_ignore_case(std::string_view a, std::string_view b);
  // Shortens untrusted text for quoting in a message.
  static std::string quote(std::string_view text);

 private:
  void skip_space_and_comments();
  bool fail_missing(const char* what);
  bool parse_double(std::string_view token, double* value, const char* what);
  bool fail_number(std::string_view token, const char* what, const char* problem);
  bool check_not_truncated(std::string_view token, const char* what);

  const char* pos_;
  const char* end_;
  const std::string& name_;
  char comment_;
  size_t line_;
  size_t token_line_;
  const char* byte_base_ = nullptr;
  bool number_may_end_text_ = false;
  bool failed_ = false;
  std::string error_;
};

}  // namespace tetlod::io
