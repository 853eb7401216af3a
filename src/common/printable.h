// Text from users (a script line, an environment variable's value) as messages show it: one line, bounded.
#pragma once
#include <cstddef>
#include <string>

namespace wb {

// At most `maxChars` characters of `text`, control characters as '?', and "... (N bytes)" when cut.
inline std::string printableExcerpt(const std::string& text, size_t maxChars = 80) {
  std::string s;
  for (unsigned char c : text.substr(0, maxChars)) s += c < 0x20 || c == 0x7f ? '?' : char(c);
  if (text.size() > maxChars) s += "... (" + std::to_string(text.size()) + " bytes)";
  return s;
}

}  // namespace wb
