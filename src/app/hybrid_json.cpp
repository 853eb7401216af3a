#include "app/hybrid_json.h"

namespace wb::app {

nlohmann::json hybridSettingsJson(const render::HybridRenderer& hybrid) {
  const auto& h = hybrid.hybridSettings();
  return {{"sun_cos_angle", hybrid.sunCosAngle()},
          {"ao_radius", hybrid.aoRadius()},
          {"ao_rays", h.aoRays},
          {"temporal", h.temporal},
          {"reflection_depth", h.reflectionDepth},
          {"reflection_max_roughness", h.reflectionMaxRoughness},
          {"reflection_min_metallic", h.reflectionMinMetallic}};
}

}  // namespace wb::app
