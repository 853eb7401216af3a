// Every parameter a user sets, declared once: its name (for `set`, scripts and JSON), CLI flag, type, valid
// range, default (the structs' defaults), whether changing it restarts accumulation, which modes use it, and
// its help text. The CLI flags (app/parameter_cli.h), `set` / `--set`, the window's panel, the JSON writers
// (app/parameter_json.h) and the key of cached reference images are all generated from this list.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>
#include <glm/glm.hpp>

#include "eval/image.h"
#include "render/hybrid/hybrid_settings.h"
#include "render/settings.h"

namespace wb::render {

// How radiance is shown (the window, PNG files); changing it never restarts accumulation.
struct DisplaySettings {
  float exposure = 0.0f;  // stops
  eval::Tonemap tonemap = eval::Tonemap::Aces;
  uint32_t view = 0;          // WB_VIEW_* (display/display_types.h)
  float denoiseSplit = 0.0f;  // with denoise on: raw left of this fraction of the view, denoised right of it
};

// Every parameter's value.
struct Parameters {
  RenderSettings render;  // its width, height, tile size and defines are launch options, not parameters
  HybridSettings hybrid;
  RenderMode mode = RenderMode::PathTrace;
  DisplaySettings display;
};

using ParameterValue = std::variant<bool, uint32_t, float, glm::vec3, std::string>;

enum class ParameterType { Bool, UInt, Float, Color, Choice, Path };

// The modes a parameter affects (bit 1 << RenderMode).
inline constexpr uint32_t kPathTraceMode = 1u << uint32_t(RenderMode::PathTrace);
inline constexpr uint32_t kHybridModes =
    (1u << uint32_t(RenderMode::Hybrid)) | (1u << uint32_t(RenderMode::Reflections));
inline constexpr uint32_t kReflectionsMode = 1u << uint32_t(RenderMode::Reflections);
inline constexpr uint32_t kAllModes = kPathTraceMode | kHybridModes;

struct ParameterInfo {
  std::string name;  // "max_bounces"
  std::string flag;  // "--max-bounces"; for a Bool, the flag that sets it to `flagSets` ("--no-rr")
  ParameterType type = ParameterType::Float;
  std::string group;  // the panel section
  std::string label;  // the panel's label
  std::string help;
  double min = 0, max = 0;      // valid values, inclusive (UInt, Float, each Color channel; floats finite)
  double uiMin = 0, uiMax = 0;  // the panel's slider; uiMin == uiMax: an input field
  std::vector<std::string> choices;
  bool flagSets = true;  // Bool: the value its flag sets
  bool resetsAccumulation = true;
  uint32_t modes = kAllModes;
  std::function<ParameterValue(const Parameters&)> get;
  std::function<void(Parameters&, const ParameterValue&)> put;

  bool usedIn(RenderMode m) const { return (modes >> uint32_t(m)) & 1u; }
};

const std::vector<ParameterInfo>& parameterList();

// A parameter by its name or its flag, with or without dashes, '-' or '_' alike ("max_bounces",
// "max-bounces", "--max-bounces"; "no_rr" finds russian_roulette through its flag). nullptr when unknown.
struct ParameterMatch {
  const ParameterInfo* info = nullptr;
  bool byFlag = false;  // matched a Bool's flag name that differs from its name (the value says "flag given")
};
ParameterMatch findParameter(const std::string& nameOrFlag);

// Parses text as the parameter's value: numbers finite and in range, a choice among choices, colours as
// R,G,B, booleans as on/off/1/0/true/false. Throws std::invalid_argument("NAME: reason").
ParameterValue parseParameter(const ParameterInfo& p, const std::string& text);
std::string formatParameter(const ParameterInfo& p, const Parameters& values);

// `set NAME VALUE`: finds, parses, applies and checks the rules between parameters; on any error throws
// std::invalid_argument and leaves `values` unchanged. A Bool found by its flag takes "flag given" values
// (set no_rr on == --no-rr).
void setParameter(Parameters& values, const std::string& nameOrFlag, const std::string& text);
// `NAME=VALUE` (a `--set` argument) split at the first '='; nullopt when there is none.
std::optional<std::pair<std::string, std::string>> splitAssignment(const std::string& assignment);
// setParameter for each `NAME=VALUE` in turn. Throws std::invalid_argument on a text without '=' or one that
// setParameter refuses; the assignments before it stay applied.
void setParameters(Parameters& values, const std::vector<std::string>& assignments);
// The rules between parameters (0 < rr_min <= rr_max <= 1). Throws std::invalid_argument.
void validateParameters(const Parameters& values);
// The parameters that restart accumulation and differ between a and b.
std::vector<const ParameterInfo*> changedParameters(const Parameters& a, const Parameters& b);
// Every parameter that changes the image, as "name=value;...": part of the key of a cached render.
std::string imageKey(const Parameters& values);
// The names, comma separated, for help texts.
std::string parameterNames();

// The display pass's views, by WB_VIEW_* number ("beauty", "albedo", ...).
const std::vector<std::string>& displayViewNames();

}  // namespace wb::render
