#include "render/settings.h"

namespace wb::render {

const std::vector<std::string>& samplerNames() {
  static const std::vector<std::string> names = {"sobol", "pcg"};
  return names;
}

const char* renderModeName(RenderMode m) {
  switch (m) {
    case RenderMode::Hybrid:
      return "hybrid";
    case RenderMode::Reflections:
      return "reflections";
    default:
      return "pathtrace";
  }
}

std::optional<RenderMode> parseRenderMode(const std::string& text) {
  if (text == "pathtrace") return RenderMode::PathTrace;
  if (text == "hybrid") return RenderMode::Hybrid;
  if (text == "reflections") return RenderMode::Reflections;
  return std::nullopt;
}

}  // namespace wb::render
