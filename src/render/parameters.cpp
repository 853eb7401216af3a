#include "render/parameters.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "common/numbers.h"
#include "display/display_types.h"
#include "shared/hybrid_types.h"

namespace wb::render {
namespace {

constexpr double kFloatMax = std::numeric_limits<float>::max();

std::string normalized(std::string s) {
  while (!s.empty() && s.front() == '-') s.erase(s.begin());
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

std::string formatNumber(double v) {
  std::ostringstream o;
  o.precision(9);
  o << v;
  return o.str();
}

ParameterInfo boolean(std::string name, std::string flag, bool flagSets, std::string group, std::string label,
                      std::string help, uint32_t modes, std::function<bool&(Parameters&)> field) {
  ParameterInfo p;
  p.name = std::move(name);
  p.flag = std::move(flag);
  p.type = ParameterType::Bool;
  p.flagSets = flagSets;
  p.group = std::move(group);
  p.label = std::move(label);
  p.help = std::move(help);
  p.modes = modes;
  p.get = [field](const Parameters& v) { return ParameterValue(field(const_cast<Parameters&>(v))); };
  p.put = [field](Parameters& v, const ParameterValue& x) { field(v) = std::get<bool>(x); };
  return p;
}

ParameterInfo unsignedInt(std::string name, std::string group, std::string label, std::string help,
                          double min, double max, double uiMin, double uiMax, uint32_t modes,
                          std::function<uint32_t&(Parameters&)> field) {
  ParameterInfo p;
  p.name = std::move(name);
  p.flag = "--" + p.name;
  std::replace(p.flag.begin(), p.flag.end(), '_', '-');
  p.type = ParameterType::UInt;
  p.group = std::move(group);
  p.label = std::move(label);
  p.help = std::move(help);
  p.min = min;
  p.max = max;
  p.uiMin = uiMin;
  p.uiMax = uiMax;
  p.modes = modes;
  p.get = [field](const Parameters& v) { return ParameterValue(field(const_cast<Parameters&>(v))); };
  p.put = [field](Parameters& v, const ParameterValue& x) { field(v) = std::get<uint32_t>(x); };
  return p;
}

ParameterInfo real(std::string name, std::string group, std::string label, std::string help, double min,
                   double max, double uiMin, double uiMax, uint32_t modes,
                   std::function<float&(Parameters&)> field) {
  ParameterInfo p = unsignedInt(std::move(name), std::move(group), std::move(label), std::move(help), min,
                                max, uiMin, uiMax, modes, nullptr);
  p.type = ParameterType::Float;
  p.get = [field](const Parameters& v) { return ParameterValue(field(const_cast<Parameters&>(v))); };
  p.put = [field](Parameters& v, const ParameterValue& x) { field(v) = std::get<float>(x); };
  return p;
}

template <class Enum>
ParameterInfo choice(std::string name, std::string group, std::string label, std::string help,
                     std::vector<std::string> choices, uint32_t modes,
                     std::function<Enum&(Parameters&)> field) {
  ParameterInfo p = unsignedInt(std::move(name), std::move(group), std::move(label), std::move(help), 0, 0, 0,
                                0, modes, nullptr);
  p.type = ParameterType::Choice;
  p.choices = choices;
  p.get = [field, choices](const Parameters& v) {
    return ParameterValue(choices.at(size_t(field(const_cast<Parameters&>(v)))));
  };
  p.put = [field, choices](Parameters& v, const ParameterValue& x) {
    const auto it = std::find(choices.begin(), choices.end(), std::get<std::string>(x));
    field(v) = Enum(it - choices.begin());
  };
  return p;
}

std::vector<std::string> viewNames() {
  return {"beauty",  "albedo", "shading_normal", "geometric_normal", "depth", "bounces",
          "dropped", "rr_end", "variance",       "nan_source",       "cost",  "inefficiency"};
}

std::vector<ParameterInfo> makeList() {
  using P = Parameters;
  std::vector<ParameterInfo> l;
  l.push_back(choice<RenderMode>(
      "mode", "Render", "mode",
      "pathtrace (reference), hybrid (raster + ray traced shadows/AO) or reflections (hybrid + ray traced "
      "reflections); with hybrid modes --spp is the number of frames",
      {"pathtrace", "hybrid", "reflections"}, kAllModes, [](P& p) -> RenderMode& { return p.mode; }));
  l.push_back(unsignedInt("spp", "Render", "target spp (0 = endless)",
                          "samples per pixel (the window: stop there; 0 = keep refining)", 0, 1u << 20, 0, 0,
                          kAllModes, [](P& p) -> uint32_t& { return p.render.spp; }));
  l.back().resetsAccumulation = false;
  l.push_back(unsignedInt("max_bounces", "Render", "max bounces",
                          "last bounce of a path (0 = the camera ray's hit)", 0, 1024, 0, 32, kPathTraceMode,
                          [](P& p) -> uint32_t& { return p.render.maxBounces; }));
  l.push_back(boolean("russian_roulette", "--no-rr", false, "Render", "Russian roulette",
                      "Russian roulette (--no-rr: disable)", kPathTraceMode,
                      [](P& p) -> bool& { return p.render.russianRoulette; }));
  l.push_back(unsignedInt("rr_start", "Render", "RR start bounce",
                          "first bounce where Russian roulette may end a path (0 = the camera ray's hit)", 0,
                          1024, 0, 16, kPathTraceMode, [](P& p) -> uint32_t& { return p.render.rrStart; }));
  l.push_back(real("rr_min", "Render", "RR min", "lowest Russian roulette survival probability", 0, 1, 0.01,
                   1, kPathTraceMode, [](P& p) -> float& { return p.render.rrMin; }));
  l.push_back(real("rr_max", "Render", "RR max", "highest Russian roulette survival probability", 0, 1, 0.01,
                   1, kPathTraceMode, [](P& p) -> float& { return p.render.rrMax; }));
  l.push_back(real("rr_exponent", "Render", "RR exponent",
                   "Russian roulette survival = clamp(max throughput ^ E, rr-min, rr-max); 0.5: square root "
                   "(Cycles), 1: proportional",
                   0, 4, 0, 1, kPathTraceMode, [](P& p) -> float& { return p.render.rrExponent; }));
  l.push_back(boolean("nee", "--no-nee", false, "Render", "NEE",
                      "next-event estimation (--no-nee: BRDF sampling only)", kPathTraceMode,
                      [](P& p) -> bool& { return p.render.nee; }));
  l.push_back(boolean("mis", "--no-mis", false, "Render", "MIS",
                      "MIS of light and BRDF sampling (--no-mis: light sampling only)", kPathTraceMode,
                      [](P& p) -> bool& { return p.render.mis; }));
  l.push_back(choice<SamplerKind>(
      "sampler", "Render", "sampler",
      "sample sequence: owen (Owen-scrambled Sobol), sobol (Sobol + blue noise), pcg", samplerNames(),
      kPathTraceMode, [](P& p) -> SamplerKind& { return p.render.sampler; }));
  l.push_back(unsignedInt("seed", "Render", "seed", "random seed", 0, 4294967295.0, 0, 0, kAllModes,
                          [](P& p) -> uint32_t& { return p.render.seed; }));
  l.push_back(
      boolean("denoise", "--denoise", true, "Render", "denoise",
              "denoise the path tracer's image (edge-avoiding a-trous guided by albedo, normal, depth "
              "and variance; hands over to the raw image as samples accumulate; the window: on)",
              kPathTraceMode, [](P& p) -> bool& { return p.render.denoise; }));
  l.back().resetsAccumulation = false;  // a filter of the accumulation: part of no reference's key
  l.push_back(boolean("generic", "--generic", true, "Render", "generic shaders",
                      "all-features shaders instead of the scene-specialised build", kPathTraceMode,
                      [](P& p) -> bool& { return p.render.generic; }));

  ParameterInfo env;
  env.name = "env";
  env.flag = "--env";
  env.type = ParameterType::Path;
  env.group = "Environment";
  env.label = "map (.hdr)";
  env.help = "equirectangular .hdr environment map (empty: the constant colour)";
  env.get = [](const P& p) { return ParameterValue(p.render.envPath); };
  env.put = [](P& p, const ParameterValue& x) { p.render.envPath = std::get<std::string>(x); };
  l.push_back(env);
  ParameterInfo color = env;
  color.name = "env_color";
  color.flag = "--env-color";
  color.type = ParameterType::Color;
  color.label = "constant colour";
  color.help = "constant environment radiance R,G,B";
  color.min = 0;
  color.max = kFloatMax;
  color.get = [](const P& p) { return ParameterValue(p.render.envColor); };
  color.put = [](P& p, const ParameterValue& x) { p.render.envColor = std::get<glm::vec3>(x); };
  l.push_back(color);
  l.push_back(real("env_rotation", "Environment", "rotation (deg)", "environment rotation about +Y, degrees",
                   -360, 360, -180, 180, kAllModes, [](P& p) -> float& { return p.render.envRotationDeg; }));
  l.push_back(real("env_intensity", "Environment", "intensity", "environment intensity multiplier", 0,
                   kFloatMax, 0, 10, kAllModes, [](P& p) -> float& { return p.render.envIntensity; }));

  l.push_back(real("sun_angle", "Environment", "sun angle (deg)",
                   "the directional lights' angular diameter in degrees, every mode (0: delta lights, hard "
                   "shadows; default: the scene's, glTF lights are delta lights; the real sun: 0.53)",
                   0, 90, 0, 10, kAllModes, [](P& p) -> float& { return p.render.sunAngleDeg; }));
  l.push_back(real("ao_radius", "Hybrid", "AO radius",
                   "hybrid: ambient occlusion ray length (0: 15% of the camera distance)", 0, kFloatMax, 0, 0,
                   kHybridModes, [](P& p) -> float& { return p.hybrid.aoRadius; }));
  l.push_back(unsignedInt(
      "ao_rays", "Hybrid", "AO rays", "hybrid: ambient occlusion rays per pixel and frame (0 = off)", 0,
      WB_HYBRID_INSPECT_MAX_AO, 0, 16, kHybridModes, [](P& p) -> uint32_t& { return p.hybrid.aoRays; }));
  l.push_back(boolean("temporal", "--no-temporal", false, "Hybrid", "temporal accumulation",
                      "hybrid: accumulate shadows/AO over frames (--no-temporal: do not)", kHybridModes,
                      [](P& p) -> bool& { return p.hybrid.temporal; }));
  l.push_back(unsignedInt("reflection_depth", "Hybrid", "reflection depth", "reflections: mirror bounces", 0,
                          WB_HYBRID_INSPECT_MAX_REFLECTIONS, 0, 8, kReflectionsMode,
                          [](P& p) -> uint32_t& { return p.hybrid.reflectionDepth; }));
  l.push_back(real("reflection_roughness", "Hybrid", "reflect below roughness",
                   "reflections: trace reflections below this roughness", 0, 1, 0, 1, kReflectionsMode,
                   [](P& p) -> float& { return p.hybrid.reflectionMaxRoughness; }));
  l.push_back(real("reflection_metallic", "Hybrid", "reflect from metallic",
                   "reflections: ... on surfaces at least this metallic (0 = smooth dielectrics too)", 0, 1,
                   0, 1, kReflectionsMode, [](P& p) -> float& { return p.hybrid.reflectionMinMetallic; }));

  l.push_back(real("exposure", "Display", "exposure (stops)", "exposure of the tonemapped image, in stops",
                   -30, 30, -8, 8, kAllModes, [](P& p) -> float& { return p.display.exposure; }));
  l.back().resetsAccumulation = false;
  l.push_back(choice<eval::Tonemap>("tonemap", "Display", "tonemapper",
                                    "tonemapper of PNG files and the window", {"clamp", "reinhard", "aces"},
                                    kAllModes, [](P& p) -> eval::Tonemap& { return p.display.tonemap; }));
  l.back().resetsAccumulation = false;
  ParameterInfo view = choice<uint32_t>(
      "view", "Display", "debug view", "what the window shows (the debug views are the path tracer's)",
      viewNames(), kAllModes, [](P& p) -> uint32_t& { return p.display.view; });
  view.resetsAccumulation = false;
  view.flag.clear();  // window only (`--set view=...`)
  l.push_back(view);
  l.push_back(
      real("denoise_split", "Display", "split raw | denoised",
           "the window with denoise on: raw image left of this fraction of the view, denoised right of "
           "it (0: all denoised)",
           0, 1, 0, 1, kPathTraceMode, [](P& p) -> float& { return p.display.denoiseSplit; }));
  l.back().resetsAccumulation = false;
  l.back().flag.clear();  // window only (`--set denoise_split=0.5`)
  return l;
}

}  // namespace

const std::vector<ParameterInfo>& parameterList() {
  static const std::vector<ParameterInfo> list = makeList();
  return list;
}

const std::vector<std::string>& displayViewNames() {
  static const std::vector<std::string> names = viewNames();
  return names;
}

ParameterMatch findParameter(const std::string& nameOrFlag) {
  const std::string want = normalized(nameOrFlag);
  for (const auto& p : parameterList()) {
    if (p.name == want) return {&p, false};
  }
  for (const auto& p : parameterList()) {
    if (!p.flag.empty() && normalized(p.flag) == want) return {&p, p.type == ParameterType::Bool};
  }
  return {};
}

ParameterValue parseParameter(const ParameterInfo& p, const std::string& text) {
  auto fail = [&](const std::string& why) -> std::invalid_argument {
    return std::invalid_argument(p.name + ": " + why);
  };
  auto number = [&](const std::string& t) {
    const std::optional<double> parsed = parseDecimal(t);  // decimal only: "0x10" is not 16
    if (!parsed) throw fail("'" + t + "' is not a finite decimal number");
    const double v = *parsed;
    if (v < p.min || v > p.max)
      throw fail("'" + t + "' is outside " + formatNumber(p.min) + " .. " + formatNumber(p.max));
    return v;
  };
  switch (p.type) {
    case ParameterType::Bool:
      if (text == "1" || text == "on" || text == "true") return true;
      if (text == "0" || text == "off" || text == "false") return false;
      throw fail("expected on/off, got '" + text + "'");
    case ParameterType::UInt: {
      if (text.find_first_not_of("0123456789") != std::string::npos || text.empty())
        throw fail("'" + text + "' is not a non-negative integer");
      return uint32_t(number(text));
    }
    case ParameterType::Float:
      return float(number(text));
    case ParameterType::Color: {
      std::vector<float> c;
      std::stringstream ss(text);
      std::string part;
      while (std::getline(ss, part, ',')) c.push_back(float(number(part)));
      if (c.size() != 3) throw fail("expected R,G,B, got '" + text + "'");
      return glm::vec3(c[0], c[1], c[2]);
    }
    case ParameterType::Choice: {
      if (std::find(p.choices.begin(), p.choices.end(), text) != p.choices.end()) return text;
      std::string known;
      for (const auto& c : p.choices) known += (known.empty() ? "" : ", ") + c;
      throw fail("expected one of " + known + ", got '" + text + "'");
    }
    case ParameterType::Path:
      if (text.find_first_of("\n\r") != std::string::npos) throw fail("a path has no line breaks");
      return text;
  }
  throw fail("unknown type");
}

std::string formatParameter(const ParameterInfo& p, const Parameters& values) {
  const ParameterValue v = p.get(values);
  if (const bool* b = std::get_if<bool>(&v)) return *b ? "on" : "off";
  if (const uint32_t* u = std::get_if<uint32_t>(&v)) return std::to_string(*u);
  if (const float* f = std::get_if<float>(&v)) return formatNumber(*f);
  if (const glm::vec3* c = std::get_if<glm::vec3>(&v))
    return formatNumber(c->x) + "," + formatNumber(c->y) + "," + formatNumber(c->z);
  return std::get<std::string>(v);
}

void validateParameters(const Parameters& v) {
  const auto& s = v.render;
  if (!(s.rrMin > 0.0f && s.rrMin <= s.rrMax && s.rrMax <= 1.0f))
    throw std::invalid_argument("rr_min/rr_max: need 0 < rr-min <= rr-max <= 1");
}

void setParameter(Parameters& values, const std::string& nameOrFlag, const std::string& text) {
  const ParameterMatch m = findParameter(nameOrFlag);
  if (!m.info)
    throw std::invalid_argument("unknown parameter '" + nameOrFlag + "' (known: " + parameterNames() + ")");
  ParameterValue v;
  if (m.byFlag) {  // `set no_rr on` is --no-rr
    const bool given = std::get<bool>(parseParameter(*m.info, text.empty() ? "on" : text));
    v = given ? m.info->flagSets : !m.info->flagSets;
  } else {
    v = parseParameter(*m.info, text);
  }
  Parameters next = values;
  m.info->put(next, v);
  validateParameters(next);
  values = next;
}

std::optional<std::pair<std::string, std::string>> splitAssignment(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) return std::nullopt;
  return std::make_pair(assignment.substr(0, eq), assignment.substr(eq + 1));
}

void setParameters(Parameters& values, const std::vector<std::string>& assignments) {
  for (const auto& a : assignments) {
    const auto nameValue = splitAssignment(a);
    if (!nameValue) throw std::invalid_argument("expected NAME=VALUE, got '" + a + "'");
    setParameter(values, nameValue->first, nameValue->second);
  }
}

std::vector<const ParameterInfo*> changedParameters(const Parameters& a, const Parameters& b) {
  std::vector<const ParameterInfo*> changed;
  for (const auto& p : parameterList()) {
    if (p.resetsAccumulation && p.get(a) != p.get(b)) changed.push_back(&p);
  }
  return changed;
}

std::string imageKey(const Parameters& values) {
  std::string key;
  for (const auto& p : parameterList()) {
    if (p.resetsAccumulation) key += p.name + "=" + formatParameter(p, values) + ";";
  }
  return key;
}

std::string parameterNames() {
  std::string names;
  for (const auto& p : parameterList()) names += (names.empty() ? "" : ", ") + p.name;
  return names;
}

}  // namespace wb::render
