// The path inspector's records as JSON (`render --inspect-out`; schema in docs/path_inspector.md): stable
// keys, numbers as numbers except NaN and infinities, written as the strings "nan", "inf" and "-inf".
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/path_inspector.h"

namespace wb::app {

// What the records are of: the pixel, the image and the value the path tracer accumulated there.
struct InspectContext {
  uint32_t x = 0, y = 0;
  uint32_t width = 0, height = 0;
  uint32_t samplesRequested = 0;
  std::string scene;
  glm::vec4 pixelValue{0.0f};  // rgb: the accumulation's average; a: samples averaged
  uint32_t spp = 0;            // samples traced for that pixel
};

nlohmann::json inspectJson(const InspectContext& context,
                           const std::vector<render::InspectedSample>& samples);
nlohmann::json inspectSampleJson(const render::InspectedSample& sample);
// The hybrid modes' record of the pixel's shadow, AO and reflection rays in the last frame
// ("workbench-hybrid-inspector/1").
nlohmann::json hybridInspectJson(const InspectContext& context, const gpu::HybridInspectRecord& record,
                                 const std::string& mode);

}  // namespace wb::app
