#include "shader/debug_labels.h"

#include <cstdio>

#include "shader/hash.h"

namespace wb::shader {

uint32_t debugLabelId(std::string_view text) {
  uint32_t h = 2166136261u;
  for (const char c : text) {
    h ^= uint8_t(c);
    h *= 16777619u;
  }
  return h;
}

namespace {

// Whether `out` ends with "debugPrintfEXT(" (spaces allowed): its format string stays a string.
bool afterDebugPrintf(const std::string& out) {
  size_t end = out.find_last_not_of(" \t");
  if (end == std::string::npos || out[end] != '(') return false;
  end = out.find_last_not_of(" \t", end - 1);
  constexpr std::string_view kName = "debugPrintfEXT";
  return end != std::string::npos && end + 1 >= kName.size() &&
         std::string_view(out).substr(end + 1 - kName.size(), kName.size()) == kName;
}

void addLabel(std::map<uint32_t, std::string>& labels, uint32_t id, const std::string& text) {
  auto [it, added] = labels.try_emplace(id, text);
  if (added || it->second == text) return;
  // A collision: both texts, each once.
  const std::string joined = " | " + text;
  if (it->second.find(joined) == std::string::npos) it->second += joined;
}

}  // namespace

std::string replaceDebugLabels(std::string_view s, std::map<uint32_t, std::string>* labels) {
  std::string out;
  out.reserve(s.size());
  bool blockComment = false;
  bool directive = false;  // inside a preprocessor line (continued by a final backslash)
  bool lineStart = true;   // only whitespace so far on this line
  size_t i = 0;
  while (i < s.size()) {
    const char c = s[i];
    if (blockComment) {
      if (c == '*' && i + 1 < s.size() && s[i + 1] == '/') {
        out += "*/";
        i += 2;
        blockComment = false;
        continue;
      }
      if (c == '\n') lineStart = true;
      out += c;
      ++i;
      continue;
    }
    if (c == '\n') {
      // A directive goes on after a backslash at the end of its line.
      const bool continued =
          directive && !out.empty() &&
          (out.back() == '\\' || (out.back() == '\r' && out.size() > 1 && out[out.size() - 2] == '\\'));
      directive = continued;
      lineStart = true;
      out += c;
      ++i;
      continue;
    }
    if (c == '/' && i + 1 < s.size() && s[i + 1] == '/') {  // to the end of the line
      const size_t end = s.find('\n', i);
      const size_t stop = end == std::string_view::npos ? s.size() : end;
      out.append(s.substr(i, stop - i));
      i = stop;
      continue;
    }
    if (c == '/' && i + 1 < s.size() && s[i + 1] == '*') {
      out += "/*";
      i += 2;
      blockComment = true;
      continue;
    }
    if (lineStart && c == '#') directive = true;
    if (c != ' ' && c != '\t' && c != '\r') lineStart = false;
    if (c == '"' && !directive) {
      std::string text;
      size_t j = i + 1;
      bool closed = false;
      while (j < s.size() && s[j] != '\n') {
        if (s[j] == '\\' && j + 1 < s.size() && s[j + 1] != '\n') {
          text += s[j + 1];
          j += 2;
          continue;
        }
        if (s[j] == '"') {
          closed = true;
          break;
        }
        text += s[j++];
      }
      if (closed && !afterDebugPrintf(out)) {
        const uint32_t id = debugLabelId(text);
        char literal[16];
        std::snprintf(literal, sizeof literal, "0x%08xu", id);
        out += literal;
        if (labels) addLabel(*labels, id, text);
        i = j + 1;
        continue;
      }
    }
    out += c;
    ++i;
  }
  return out;
}

std::map<uint32_t, std::string> debugLabelsOf(const std::vector<std::filesystem::path>& files) {
  std::map<uint32_t, std::string> labels;
  for (const auto& f : files) {
    const auto text = readFile(f);
    if (!text) continue;
    std::map<uint32_t, std::string> mine;
    replaceDebugLabels(*text, &mine);
    for (const auto& [id, t] : mine) addLabel(labels, id, t);
  }
  return labels;
}

}  // namespace wb::shader
