#include "app/window/workbench_state.h"

#include "app/render_options.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace wb::app {
namespace {

const char* const kViewNames[WB_VIEW_COUNT] = {"beauty", "albedo",  "shading_normal", "geometric_normal",
                                               "depth",  "bounces", "dropped"};

float toFloat(const std::string& name, const std::string& v) {
  size_t used = 0;
  float f = 0;
  try {
    f = std::stof(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || !std::isfinite(f))
    throw std::invalid_argument(name + ": '" + v + "' is not a number");
  return f;
}

uint32_t toUint(const std::string& name, const std::string& v) {
  size_t used = 0;
  unsigned long u = 0;
  try {
    u = std::stoul(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || v.empty() || v[0] == '-')
    throw std::invalid_argument(name + ": '" + v + "' is not a non-negative integer");
  return uint32_t(u);
}

bool toBool(const std::string& name, const std::string& v) {
  if (v == "1" || v == "on" || v == "true") return true;
  if (v == "0" || v == "off" || v == "false") return false;
  throw std::invalid_argument(name + ": expected on/off, got '" + v + "'");
}

glm::vec3 toVec3(const std::string& name, const std::string& v, const ParamRange* range = nullptr) {
  std::stringstream ss(v);
  std::string part;
  std::vector<float> c;
  while (std::getline(ss, part, ','))
    c.push_back(range ? float(parseParam(*range, part, name)) : toFloat(name, part));
  if (c.size() != 3) throw std::invalid_argument(name + ": expected X,Y,Z, got '" + v + "'");
  return {c[0], c[1], c[2]};
}

// A numeric setting checked as its command-line flag is (render_options.h).
float toParam(const ParamRange& p, const std::string& name, const std::string& v) {
  return float(parseParam(p, v, name));
}

}  // namespace

const char* viewName(uint32_t view) {
  return view < WB_VIEW_COUNT ? kViewNames[view] : "?";
}

std::optional<uint32_t> viewFromName(const std::string& name) {
  for (uint32_t i = 0; i < WB_VIEW_COUNT; ++i)
    if (name == kViewNames[i]) return i;
  return std::nullopt;
}

std::optional<eval::Tonemap> tonemapFromName(const std::string& name) {
  for (auto t : {eval::Tonemap::Clamp, eval::Tonemap::Reinhard, eval::Tonemap::Aces})
    if (name == eval::tonemapName(t)) return t;
  return std::nullopt;
}

const char* settingNamesHelp() {
  return "exposure, tonemap (clamp|reinhard|aces), view (beauty|albedo|shading_normal|geometric_normal|depth|"
         "bounces|dropped), max_bounces, rr_start, rr_min, rr_max, sampler (sobol|pcg), seed, spp (target, 0 "
         "= endless), paused, scale, preview, budget_ms, vsync, env_intensity, env_rotation, env_color "
         "R,G,B, "
         "env PATH, sun_direction X,Y,Z, sun_intensity, panel, material.N.roughness|metallic|base_color "
         "R,G,B, "
         "mode (pathtrace|hybrid|reflections), sun_angle, ao_rays, ao_radius, temporal, reflection_depth, "
         "reflection_roughness, reflection_metallic, reference PATH.exr (empty = noise estimate)";
}

void applySetting(WorkbenchState& st, const std::string& name, const std::string& value) {
  auto& s = st.settings;
  if (name == "exposure") {
    st.display.exposure = toParam(params::kExposure, name, value);
  } else if (name == "tonemap") {
    auto t = tonemapFromName(value);
    if (!t) throw std::invalid_argument("tonemap: expected clamp, reinhard or aces, got '" + value + "'");
    st.display.tonemap = *t;
  } else if (name == "view") {
    auto v = viewFromName(value);
    if (!v) throw std::invalid_argument("view: unknown debug view '" + value + "'");
    st.display.view = *v;
  } else if (name == "max_bounces") {
    s.maxBounces = toUint(name, value);
  } else if (name == "rr_start") {
    s.rrStart = toUint(name, value);
  } else if (name == "rr_min") {
    s.rrMin = toParam(params::kRrMin, name, value);
  } else if (name == "rr_max") {
    s.rrMax = toParam(params::kRrMax, name, value);
  } else if (name == "sampler") {
    if (value != "sobol" && value != "pcg") throw std::invalid_argument("sampler: expected sobol or pcg");
    s.sampler = value == "pcg" ? render::SamplerKind::Pcg : render::SamplerKind::Sobol;
  } else if (name == "seed") {
    s.seed = toUint(name, value);
  } else if (name == "spp") {
    st.targetSpp = toUint(name, value);
  } else if (name == "paused") {
    st.paused = toBool(name, value);
  } else if (name == "scale") {
    const float f = toFloat(name, value);
    if (f <= 0.0f || f > 2.0f) throw std::invalid_argument("scale: expected 0 < scale <= 2");
    st.resolutionScale = f;
  } else if (name == "preview") {
    st.preview = toBool(name, value);
  } else if (name == "budget_ms") {
    st.budgetMs = toParam(params::kBudgetMs, name, value);
  } else if (name == "vsync") {
    st.vsync = toBool(name, value);
  } else if (name == "panel") {
    st.showPanel = toBool(name, value);
  } else if (name == "env_intensity") {
    s.envIntensity = toParam(params::kEnvIntensity, name, value);
  } else if (name == "env_rotation") {
    s.envRotationDeg = toParam(params::kEnvRotation, name, value);
  } else if (name == "env_color") {
    s.envColor = toVec3(name, value, &params::kEnvColor);
  } else if (name == "env") {
    s.envPath = value;
  } else if (name == "sun_direction" || name == "sun_intensity") {
    if (st.lights.empty()) throw std::invalid_argument(name + ": the scene has no directional light");
    auto& l = st.lights[0];
    if (name == "sun_direction") {
      const glm::vec3 d = toVec3(name, value);
      if (!(glm::length(d) > 1e-6f)) throw std::invalid_argument(name + ": the direction has no length");
      l.direction = glm::normalize(d);
    } else {
      const float old = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
      const float want = toParam(params::kSunIntensity, name, value);
      l.radiance = old > 0.0f ? l.radiance * (want / old) : glm::vec3(want);
    }
    st.lightsDirty = true;
  } else if (name == "mode") {
    const auto m = render::parseRenderMode(value);
    if (!m)
      throw std::invalid_argument("mode: expected pathtrace, hybrid or reflections, got '" + value + "'");
    st.mode = *m;
  } else if (name == "sun_angle") {
    st.hybrid.sunAngleDeg = toParam(params::kSunAngle, name, value);
  } else if (name == "ao_rays") {
    st.hybrid.aoRays = toUint(name, value);
  } else if (name == "ao_radius") {
    st.hybrid.aoRadius = toParam(params::kAoRadius, name, value);
  } else if (name == "temporal") {
    st.hybrid.temporal = toBool(name, value);
  } else if (name == "reflection_depth") {
    const uint32_t d = toUint(name, value);
    if (d > 16) throw std::invalid_argument("reflection_depth: at most 16");
    st.hybrid.reflectionDepth = d;
  } else if (name == "reflection_roughness") {
    st.hybrid.reflectionMaxRoughness = toParam(params::kReflectionRoughness, name, value);
  } else if (name == "reflection_metallic") {
    st.hybrid.reflectionMinMetallic = toParam(params::kReflectionMetallic, name, value);
  } else if (name == "reference") {
    st.referencePath = value;
  } else if (name.rfind("material.", 0) == 0) {
    const auto dot = name.find('.', 9);
    if (dot == std::string::npos) throw std::invalid_argument(name + ": expected material.N.FIELD");
    const uint32_t index = toUint(name, name.substr(9, dot - 9));
    if (index >= st.materials.size())
      throw std::invalid_argument(name + ": no material " + std::to_string(index));
    auto& m = st.materials[index];
    const std::string field = name.substr(dot + 1);
    if (field == "roughness") {
      m.roughness = toParam(params::kMaterialFactor, name, value);
    } else if (field == "metallic") {
      m.metallic = toParam(params::kMaterialFactor, name, value);
    } else if (field == "base_color") {
      const glm::vec3 c = toVec3(name, value, &params::kMaterialFactor);
      m.baseColorFactor = glm::vec4(c, m.baseColorFactor.w);
    } else {
      throw std::invalid_argument(name + ": unknown material field '" + field + "'");
    }
    st.materialsDirty = true;
  } else {
    throw std::invalid_argument("unknown setting '" + name + "' (known: " + settingNamesHelp() + ")");
  }
}

}  // namespace wb::app
