#include "live/session_state.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <cstdint>
#include <stdexcept>

#include "common/numbers.h"

namespace wb::live {
namespace {

float toFloat(const std::string& name, const std::string& v) {
  const auto d = parseDecimal(v);  // decimal only
  if (!d || !std::isfinite(float(*d)))
    throw std::invalid_argument(name + ": '" + v + "' is not a finite decimal number");
  return float(*d);
}

uint32_t toUint(const std::string& name, const std::string& v) {
  const auto u = parseDecimalUnsigned(v);
  if (!u || *u > UINT32_MAX)
    throw std::invalid_argument(name + ": '" + v +
                                "' is not a non-negative decimal integer (at most 2^32 - 1)");
  return uint32_t(*u);
}

bool toBool(const std::string& name, const std::string& v) {
  if (v == "1" || v == "on" || v == "true") return true;
  if (v == "0" || v == "off" || v == "false") return false;
  throw std::invalid_argument(name + ": expected on/off, got '" + v + "'");
}

glm::vec3 toVec3(const std::string& name, const std::string& v) {
  std::stringstream ss(v);
  std::string part;
  std::vector<float> c;
  while (std::getline(ss, part, ',')) c.push_back(toFloat(name, part));
  if (c.size() != 3) throw std::invalid_argument(name + ": expected X,Y,Z, got '" + v + "'");
  return {c[0], c[1], c[2]};
}

const char* kWindowSettings =
    "scale, preview, budget_ms, vsync, panel, paused, reference PATH.exr (empty = noise estimate), "
    "sun_direction X,Y,Z, sun_intensity, material.N.roughness|metallic|base_color R,G,B, "
    "inspect_pixel X,Y|off, inspect_samples N, inspect_on_click, inspect_all, asserts";

// The window's own settings (not render parameters). False when `name` is none of them.
bool applyWindowSetting(SessionState& st, const std::string& name, const std::string& value) {
  if (name == "scale") {
    const float f = toFloat(name, value);
    if (f <= 0.0f || f > 2.0f) throw std::invalid_argument("scale: expected 0 < scale <= 2");
    st.resolutionScale = f;
  } else if (name == "preview") {
    st.preview = toBool(name, value);
  } else if (name == "budget_ms") {
    const float f = toFloat(name, value);
    if (f < 1.0f || f > 10000.0f) throw std::invalid_argument("budget_ms: expected 1 .. 10000");
    st.budgetMs = f;
  } else if (name == "vsync") {
    st.vsync = toBool(name, value);
  } else if (name == "panel") {
    st.showPanel = toBool(name, value);
  } else if (name == "paused") {
    st.paused = toBool(name, value);
  } else if (name == "reference") {
    st.referencePath = value;
  } else if (name == "inspect_pixel") {
    if (value == "off") {
      st.inspectPixel.reset();
    } else {
      const auto comma = value.find(',');
      if (comma == std::string::npos) throw std::invalid_argument("inspect_pixel: expected X,Y or off");
      st.inspectPixel =
          glm::uvec2(toUint(name, value.substr(0, comma)), toUint(name, value.substr(comma + 1)));
      st.inspectOpenPanel = 2;
    }
  } else if (name == "inspect_samples") {
    const uint32_t n = toUint(name, value);
    if (n < 1 || n > 4096) throw std::invalid_argument("inspect_samples: expected 1 .. 4096");
    st.inspectSamples = n;
  } else if (name == "inspect_on_click") {
    st.inspectOnClick = toBool(name, value);
  } else if (name == "inspect_all") {
    st.inspectAllSamples = toBool(name, value);
  } else if (name == "asserts") {
    st.asserts = toBool(name, value);
  } else if (name == "sun_direction" || name == "sun_intensity") {
    if (st.lights.empty()) throw std::invalid_argument(name + ": the scene has no directional light");
    auto& l = st.lights[0];
    if (name == "sun_direction") {
      const glm::vec3 d = toVec3(name, value);
      if (!(glm::length(d) > 0.0f)) throw std::invalid_argument("sun_direction: must not be zero");
      l.direction = glm::normalize(d);
    } else {
      const float old = std::max({l.radiance.x, l.radiance.y, l.radiance.z});
      const float want = toFloat(name, value);
      if (want < 0.0f) throw std::invalid_argument("sun_intensity: must be non-negative");
      l.radiance = old > 0.0f ? l.radiance * (want / old) : glm::vec3(want);
    }
    st.lightsDirty = true;
  } else if (name.rfind("material.", 0) == 0) {
    const auto dot = name.find('.', 9);
    if (dot == std::string::npos) throw std::invalid_argument(name + ": expected material.N.FIELD");
    const uint32_t index = toUint(name, name.substr(9, dot - 9));
    if (index >= st.materials.size())
      throw std::invalid_argument(name + ": no material " + std::to_string(index));
    auto& m = st.materials[index];
    const std::string field = name.substr(dot + 1);
    auto unit = [&](float f) {
      if (f < 0.0f || f > 1.0f) throw std::invalid_argument(name + ": expected 0 .. 1");
      return f;
    };
    if (field == "roughness") {
      m.roughness = unit(toFloat(name, value));
    } else if (field == "metallic") {
      m.metallic = unit(toFloat(name, value));
    } else if (field == "base_color") {
      const glm::vec3 c = toVec3(name, value);
      if (c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
        throw std::invalid_argument(name + ": must be non-negative");
      m.baseColorFactor = glm::vec4(c, m.baseColorFactor.w);
    } else {
      throw std::invalid_argument(name + ": unknown material field '" + field + "'");
    }
    st.materialsDirty = true;
  } else {
    return false;
  }
  return true;
}

}  // namespace

std::string settingNamesHelp() {
  return render::parameterNames() + " (as their flags too: no_rr, no_nee, ...); " + kWindowSettings;
}

void applySetting(SessionState& st, const std::string& name, const std::string& value) {
  if (render::findParameter(name).info) {
    render::setParameter(st.params, name, value);
    return;
  }
  if (!applyWindowSetting(st, name, value))
    throw std::invalid_argument("unknown setting '" + name + "' (known: " + settingNamesHelp() + ")");
}

}  // namespace wb::live
