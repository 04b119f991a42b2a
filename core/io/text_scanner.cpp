#include "core/io/text_scanner.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

namespace tetlod::io {
namespace {

inline bool is_space(char c) {
  return c == ' ' || (c >= '\t' && c <= '\r');
}

// std::from_chars rejects a leading '+', which some writers (Fortran) emit.
inline const char* skip_plus(const char* first, const char* last) {
  if (last - first >= 2 && first[0] == '+' &&
      (first[1] == '.' || (first[1] >= '0' && first[1] <= '9')))
    return first + 1;
  return first;
}

// from_chars reports result_out_of_range for both overflow and underflow. A value
// too small for a double is read as a signed zero (it is zero to double precision);
// an overflow stays an error. Underflow: a negative exponent, or no exponent and a
// zero integer part ("0.000...1").
bool is_underflow(std::string_view token) {
  const size_t e = token.find_first_of("eE");
  if (e != std::string_view::npos) return e + 1 < token.size() && token[e + 1] == '-';
  for (char c : token) {
    if (c == '.') return true;
    if (c >= '1' && c <= '9') return false;
  }
  return true;
}

}  // namespace

TextScanner::TextScanner(std::string_view text, const std::string& name, char comment,
                         size_t first_line)
    : pos_(text.data()),
      end_(text.data() + text.size()),
      name_(name),
      comment_(comment),
      line_(first_line),
      token_line_(first_line) {
  // A UTF-8 byte order mark some Windows editors put first.
  if (text.size() >= 3 && std::memcmp(pos_, "\xEF\xBB\xBF", 3) == 0) pos_ += 3;
}

void TextScanner::skip_space_and_comments() {
  while (pos_ < end_) {
    const char c = *pos_;
    if (c == '\n') {
      ++line_;
      ++pos_;
    } else if (is_space(c)) {
      ++pos_;
    } else if (comment_ != 0 && c == comment_) {
      const void* newline = std::memchr(pos_, '\n', size_t(end_ - pos_));
      pos_ = newline ? static_cast<const char*>(newline) : end_;
    } else {
      break;
    }
  }
}

bool TextScanner::next_token(std::string_view* token) {
  skip_space_and_comments();
  if (pos_ == end_) return false;  // errors at the end name the line of the last token
  token_line_ = line_;
  const char* start = pos_;
  while (pos_ < end_ && !is_space(*pos_)) ++pos_;
  *token = std::string_view(start, size_t(pos_ - start));
  return true;
}

bool TextScanner::peek_token(std::string_view* token) {
  const char* saved_pos = pos_;
  const size_t saved_line = line_;
  const size_t saved_token_line = token_line_;
  const bool found = next_token(token);
  pos_ = saved_pos;
  line_ = saved_line;
  token_line_ = saved_token_line;
  return found;
}

bool TextScanner::at_end() {
  skip_space_and_comments();
  return pos_ == end_;
}

bool TextScanner::check_not_truncated(std::string_view token, const char* what) {
  if (number_may_end_text_ || token.data() + token.size() != end_) return true;
  return fail(std::string("the file ends inside ") + what + " " + quote(token) +
              " (truncated file?)");
}

bool TextScanner::read_double(double* value, const char* what) {
  std::string_view token;
  if (!next_token(&token)) return fail_missing(what);
  return parse_double(token, value, what);
}

bool TextScanner::parse_double(std::string_view token, double* value, const char* what) {
  const char* last = token.data() + token.size();
  const char* first = skip_plus(token.data(), last);
  auto [ptr, ec] = std::from_chars(first, last, *value);
  if (ec == std::errc::result_out_of_range && ptr == last) {
    if (!is_underflow(token)) return fail_number(token, what, "is not a finite number (overflow)");
    *value = *first == '-' ? -0.0 : 0.0;
    ec = std::errc();
  }
  if (ec != std::errc() || ptr != last) return fail_number(token, what, "is not a number");
  if (!std::isfinite(*value)) return fail_number(token, what, "is not a finite number");
  return check_not_truncated(token, what);
}

bool TextScanner::read_int(int64_t* value, const char* what) {
  std::string_view token;
  if (!next_token(&token)) return fail_missing(what);
  const char* last = token.data() + token.size();
  const char* first = skip_plus(token.data(), last);
  auto [ptr, ec] = std::from_chars(first, last, *value);
  if (ec == std::errc::result_out_of_range) return fail_number(token, what, "is out of range");
  if (ec != std::errc() || ptr != last) return fail_number(token, what, "is not an integer");
  return check_not_truncated(token, what);
}

bool TextScanner::read_int_in_range(int64_t* value, const char* what, int64_t min_value,
                                    int64_t max_value) {
  if (!read_int(value, what)) return false;
  if (*value < min_value || *value > max_value) {
    return fail(std::string(what) + " " + std::to_string(*value) + " is out of range [" +
                std::to_string(min_value) + ", " + std::to_string(max_value) + "]");
  }
  return true;
}

bool TextScanner::read_integral(int64_t* value, const char* what, int64_t min_value,
                                int64_t max_value) {
  double number = 0;
  std::string_view token;
  if (!next_token(&token)) return fail_missing(what);
  if (!parse_double(token, &number, what)) return false;
  // The range tests come first so that the conversion to int64_t is defined.
  constexpr double kTwoTo63 = 9223372036854775808.0;
  if (!(number >= -kTwoTo63 && number < kTwoTo63) || number != std::floor(number) ||
      int64_t(number) < min_value || int64_t(number) > max_value) {
    return fail(std::string(what) + " " + quote(token) + " is not an integer in [" +
                std::to_string(min_value) + ", " + std::to_string(max_value) + "]");
  }
  *value = int64_t(number);
  return true;
}

bool TextScanner::read_count(uint64_t* count, const char* what, uint64_t min_bytes_per_item) {
  int64_t value = 0;
  if (!read_int(&value, what)) return false;
  if (value < 0) return fail(std::string(what) + " " + std::to_string(value) + " is negative");
  // The last item may lack its trailing separator, hence the + 1.
  const uint64_t capacity = min_bytes_per_item == 0
                                ? std::numeric_limits<uint64_t>::max()
                                : (uint64_t(remaining_bytes()) + 1) / min_bytes_per_item;
  if (uint64_t(value) > capacity) {
    return fail(std::string(what) + " " + std::to_string(value) +
                " is larger than the rest of the file can hold (wrong count or truncated file?)");
  }
  *count = uint64_t(value);
  return true;
}

bool TextScanner::skip_numbers(uint64_t count, const char* what) {
  std::string_view token;
  for (uint64_t i = 0; i < count; ++i) {
    if (!next_token(&token)) return fail_missing(what);
    if (!looks_numeric(token)) {
      return fail(std::string("expected a number in ") + what + ", found " + quote(token) +
                  " (wrong count?)");
    }
  }
  return true;
}

bool TextScanner::expect_keyword(std::string_view keyword) {
  std::string_view token;
  const std::string expected = "'" + std::string(keyword) + "'";
  if (!next_token(&token)) return fail_missing(expected.c_str());
  if (!equals_ignore_case(token, keyword)) {
    return fail("expected " + expected + ", found " + quote(token));
  }
  return true;
}

std::string_view TextScanner::rest_of_line() {
  token_line_ = line_;
  const char* start = pos_;
  const void* newline = std::memchr(pos_, '\n', size_t(end_ - pos_));
  const char* stop = newline ? static_cast<const char*>(newline) : end_;
  pos_ = stop;
  if (pos_ < end_) {
    ++pos_;
    ++line_;
  }
  if (stop > start && stop[-1] == '\r') --stop;
  return std::string_view(start, size_t(stop - start));
}

void TextScanner::advance(size_t byte_count) {
  byte_count = std::min(byte_count, remaining_bytes());
  line_ += size_t(std::count(pos_, pos_ + byte_count, '\n'));
  pos_ += byte_count;
  token_line_ = line_;
}

bool TextScanner::fail(std::string_view message) {
  return fail_at_line(token_line_, message);
}

bool TextScanner::fail_at_line(size_t line, std::string_view message) {
  if (!failed_) {
    failed_ = true;
    error_ =
        byte_base_ != nullptr
            ? name_ + ": byte " + std::to_string(pos_ - byte_base_) + ": " + std::string(message)
            : name_ + ":" + std::to_string(line) + ": " + std::string(message);
  }
  return false;
}

bool TextScanner::adopt_failure(const TextScanner& other) {
  if (!failed_) {
    failed_ = true;
    error_ = other.error_;
  }
  return false;
}

bool TextScanner::fail_missing(const char* what) {
  return fail(std::string("unexpected end of file, expected ") + what);
}

bool TextScanner::fail_number(std::string_view token, const char* what, const char* problem) {
  return fail(std::string(what) + " " + quote(token) + " " + problem);
}

bool TextScanner::looks_numeric(std::string_view token) {
  const char c = token.empty() ? ' ' : token[0];
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

bool TextScanner::equals_ignore_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    char x = a[i], y = b[i];
    if (x >= 'A' && x <= 'Z') x = char(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = char(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

std::string TextScanner::quote(std::string_view text) {
  constexpr size_t kMaxQuoted = 40;
  std::string result = "'";
  for (size_t i = 0; i < std::min(text.size(), kMaxQuoted); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    result += (c >= 32 && c < 127) ? char(c) : '?';
  }
  if (text.size() > kMaxQuoted) result += "...";
  result += "'";
  return result;
}

}  // namespace tetlod::io
