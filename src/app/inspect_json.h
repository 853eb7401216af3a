// The path inspector's records as JSON (`render --inspect-out`; schema in docs/path_inspector.md): stable
// keys, numbers as numbers except NaN and infinities, written as the strings "nan", "inf" and "-inf".
#pragma once
#include <map>
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
  glm::vec4 pixelValue{0.0f};              // rgb: the accumulation's average; a: samples averaged
  uint32_t spp = 0;                        // samples traced for that pixel
  uint32_t clock = 0;                      // the shader clock of the records' costs (WB_CLOCK_*; 0: none)
  std::map<uint32_t, std::string> labels;  // wbPrint labels (PathTracer::debugLabels)
};

nlohmann::json inspectJson(const InspectContext& context,
                           const std::vector<render::InspectedSample>& samples);
// One sample; its prints' labels from `labels`, its costs null without a clock.
nlohmann::json inspectSampleJson(const render::InspectedSample& sample,
                                 const std::map<uint32_t, std::string>& labels = {}, uint32_t clock = 0);
// The hybrid modes' record of the pixel's shadow, AO and reflection rays in the last frame
// ("workbench-hybrid-inspector/1").
nlohmann::json hybridInspectJson(const InspectContext& context, const gpu::HybridInspectRecord& record,
                                 const std::string& mode);

}  // namespace wb::app
