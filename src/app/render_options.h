// Command-line flags shared by `render`, the window and the other commands that render (a contract with
// scripts outside the project: names are stable).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "render/hybrid/hybrid_settings.h"
#include "render/settings.h"

namespace wb::app {

struct RenderOptions {
  std::string scene;  // empty = the default scene
  std::string size = "512x512";
  render::RenderSettings settings;
  std::string envColor;  // "R,G,B"
  std::string sampler = "sobol";
  std::string aov;                            // "albedo,normal"
  bool aovAlbedo = false, aovNormal = false;  // which --aov images to write
  std::vector<std::string> defines;           // --define K=V
  std::string device;
  std::string tile;  // "WxH": dispatch shape of a sample (default: the whole image)
  bool noRussianRoulette = false;
  bool noNee = false;
  bool noMis = false;
  // --mode pathtrace|hybrid|reflections and the hybrid modes' parameters.
  std::string modeName = "pathtrace";
  render::RenderMode mode = render::RenderMode::PathTrace;
  render::HybridSettings hybrid;
  bool noTemporal = false;
};

// A numeric render parameter: its command-line flag, its name for the window's --set and scripts, and the
// range its value must lie in (always finite: NaN and infinities are refused). The flags and the window check
// every value through the same table.
struct ParamRange {
  const char* flag;
  const char* setting;
  double min, max;
};
namespace params {
inline constexpr double kHuge = 3.0e38;  // just under FLT_MAX
inline constexpr ParamRange kEnvIntensity{"--env-intensity", "env_intensity", 0.0, kHuge};
inline constexpr ParamRange kEnvRotation{"--env-rotation", "env_rotation", -1e6, 1e6};
inline constexpr ParamRange kEnvColor{"--env-color", "env_color", 0.0, kHuge};
inline constexpr ParamRange kRrMin{"--rr-min", "rr_min", 1e-6, 1.0};
inline constexpr ParamRange kRrMax{"--rr-max", "rr_max", 1e-6, 1.0};
inline constexpr ParamRange kSunAngle{"--sun-angle", "sun_angle", 0.0, 90.0};
inline constexpr ParamRange kAoRadius{"--ao-radius", "ao_radius", 0.0, kHuge};
inline constexpr ParamRange kReflectionRoughness{"--reflection-roughness", "reflection_roughness", 0.0, 1.0};
inline constexpr ParamRange kReflectionMetallic{"--reflection-metallic", "reflection_metallic", 0.0, 1.0};
// The window's own.
inline constexpr ParamRange kExposure{"--exposure", "exposure", -64.0, 64.0};
inline constexpr ParamRange kBudgetMs{"--budget-ms", "budget_ms", 0.1, 1e6};
inline constexpr ParamRange kSunIntensity{"--sun-intensity", "sun_intensity", 0.0, kHuge};
inline constexpr ParamRange kMaterialFactor{"--material", "material factor", 0.0, 1.0};
}  // namespace params

// Parses text as a finite number within p's range; throws std::invalid_argument starting with `name`.
double parseParam(const ParamRange& p, const std::string& text, const std::string& name);
// A CLI11 check of the flag's value against p (the same rule).
CLI::Validator paramCheck(const ParamRange& p);

// Adds SCENE and the render parameter flags to a CLI11 command.
void addRenderOptions(CLI::App& app, RenderOptions& o);
// Validates and converts the parsed strings into o.settings; throws std::invalid_argument with a one-line
// reason.
void finishRenderOptions(RenderOptions& o);

}  // namespace wb::app
