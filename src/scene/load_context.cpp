#include "scene/load_context.h"

#include <algorithm>

namespace wb::scene {

void LoadContext::fail(const std::string& reason) const {
  throw SceneError(fileName_ + ": " + oneLine(reason));
}

void LoadContext::warn(const std::string& warning) {
  const std::string line = oneLine(warning);
  if (std::find(warnings_.begin(), warnings_.end(), line) == warnings_.end()) warnings_.push_back(line);
}

std::string oneLine(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\r') continue;
    if (c == '\n') {
      if (!out.empty() && out.back() != ' ') out += "; ";
      continue;
    }
    out += c;
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out;
}

}  // namespace wb::scene
