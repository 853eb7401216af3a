#include "render/settings.h"

namespace wb::render {

const std::vector<std::string>& samplerNames() {
  static const std::vector<std::string> names = {"sobol", "pcg", "owen"};
  return names;
}

const char* samplerName(SamplerKind k) {
  return samplerNames().at(size_t(k)).c_str();
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
