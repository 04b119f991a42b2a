// Reading text files line by line (internal to core/io), for the formats whose
// entries are lines with fixed or comma-separated fields (Nastran, Abaqus).
#pragma once

#include <algorithm>
#include <cstddef>
#include <string_view>

namespace tetlod::io {

// `s` without leading and trailing blanks (spaces, tabs, '\r').
inline std::string_view trim_blanks(std::string_view s) {
  auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

// The line of `text` at *pos, without its '\n'; moves *pos past it and counts it in
// *line (1-based). False at the end of the text.
inline bool next_text_line(std::string_view text, size_t* pos, size_t* line,
                           std::string_view* out) {
  if (*pos >= text.size()) return false;
  const size_t end = std::min(text.find('\n', *pos), text.size());
  *out = text.substr(*pos, end - *pos);
  *pos = end + 1;
  ++*line;
  return true;
}

}  // namespace tetlod::io
