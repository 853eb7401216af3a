#include "app/render_options.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "shader/types.h"

namespace wb::app {

void addRenderOptions(CLI::App& app, RenderOptions& o) {
  auto& s = o.settings;
  app.add_option("scene", o.scene, "glTF scene (.gltf/.glb); default: assets/default_scene.gltf");
  app.add_option("--size", o.size, "image size WxH")->capture_default_str();
  app.add_option("--spp", s.spp, "samples per pixel")->capture_default_str()->check(CLI::Range(1u, 1u << 20));
  app.add_option("--max-bounces", s.maxBounces, "maximum path bounces")
      ->capture_default_str()
      ->check(CLI::Range(0u, 1024u));
  app.add_option("--rr-start", s.rrStart, "first bounce where Russian roulette may end a path")
      ->capture_default_str();
  app.add_option("--rr-min", s.rrMin, "lowest Russian roulette survival probability")
      ->capture_default_str()
      ->check(paramCheck(params::kRrMin));
  app.add_option("--rr-max", s.rrMax, "highest Russian roulette survival probability")
      ->capture_default_str()
      ->check(paramCheck(params::kRrMax));
  app.add_flag("--no-rr", o.noRussianRoulette, "disable Russian roulette");
  app.add_flag("--no-nee", o.noNee, "disable next-event estimation (BRDF sampling only)");
  app.add_flag("--no-mis", o.noMis, "environment by light sampling only (no MIS with BRDF sampling)");
  app.add_option("--sampler", o.sampler, "sobol|pcg")->capture_default_str();
  app.add_option("--seed", s.seed, "random seed")->capture_default_str();
  app.add_option("--env", s.envPath,
                 "equirectangular environment: Radiance .hdr (PNG/JPEG are taken as sRGB, with a warning)");
  app.add_option("--env-color", o.envColor, "constant environment radiance R,G,B");
  app.add_option("--env-rotation", s.envRotationDeg, "environment rotation about +Y, degrees")
      ->capture_default_str()
      ->check(paramCheck(params::kEnvRotation));
  app.add_option("--env-intensity", s.envIntensity, "environment intensity multiplier")
      ->capture_default_str()
      ->check(paramCheck(params::kEnvIntensity));
  app.add_option("--aov", o.aov, "write AOVs: albedo,normal (beside --out)");
  app.add_option("--device", o.device, "Vulkan device name (substring)");
  app.add_option("--tile", o.tile, "trace each sample in tiles of WxH (dispatch-shape experiments)");
  app.add_flag("--generic", s.generic, "all-features shaders instead of the scene-specialised build");
  app.add_option("--define", o.defines,
                 "preprocessor define K=V (or K) for the path tracer's shaders; repeatable");
  app.add_option(
         "--mode", o.modeName,
         "pathtrace (reference), hybrid (raster + ray traced shadows/AO) or reflections (hybrid + ray "
         "traced reflections); with hybrid modes --spp is the number of frames")
      ->capture_default_str();
  auto& h = o.hybrid;
  app.add_option("--sun-angle", h.sunAngleDeg,
                 "hybrid: sun angular diameter in degrees for soft shadows (default: the light's, else 0.53)")
      ->check(paramCheck(params::kSunAngle));
  app.add_option("--ao-radius", h.aoRadius,
                 "hybrid: ambient occlusion ray length (default: 15% of camera distance)")
      ->check(paramCheck(params::kAoRadius));
  app.add_option("--ao-rays", h.aoRays, "hybrid: ambient occlusion rays per pixel and frame (0 = off)")
      ->capture_default_str();
  app.add_flag("--no-temporal", o.noTemporal, "hybrid: no accumulation of shadows/AO over frames");
  app.add_option("--reflection-depth", h.reflectionDepth, "reflections: mirror bounces")
      ->capture_default_str()
      ->check(CLI::Range(0u, 16u));
  app.add_option("--reflection-roughness", h.reflectionMaxRoughness,
                 "reflections: trace reflections below this roughness")
      ->capture_default_str()
      ->check(paramCheck(params::kReflectionRoughness));
  app.add_option("--reflection-metallic", h.reflectionMinMetallic,
                 "reflections: ... on surfaces at least this metallic (0 = smooth dielectrics too)")
      ->capture_default_str()
      ->check(paramCheck(params::kReflectionMetallic));
}

double parseParam(const ParamRange& p, const std::string& text, const std::string& name) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  const std::string prefix = name.empty() ? "" : name + ": ";
  if (text.empty() || used != text.size() || !std::isfinite(v))
    throw std::invalid_argument(prefix + "'" + text + "' is not a finite number");
  if (v < p.min || v > p.max) {
    std::ostringstream range;
    range << prefix << text << " is out of range [" << p.min << ", " << p.max << "]";
    throw std::invalid_argument(range.str());
  }
  return v;
}

CLI::Validator paramCheck(const ParamRange& p) {
  return CLI::Validator(
      [p](std::string& text) -> std::string {
        try {
          parseParam(p, text, "");  // CLI11 puts the flag in front
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      "", std::string("range of ") + p.flag);
}

void finishRenderOptions(RenderOptions& o) {
  auto& s = o.settings;
  unsigned w = 0, h = 0;
  char x = 0, extra = 0;
  std::istringstream size(o.size);
  if (!(size >> w >> x >> h) || (x != 'x' && x != 'X') || (size >> extra) || w == 0 || h == 0 || w > 16384 ||
      h > 16384) {
    throw std::invalid_argument("--size: expected WxH with 1..16384, got '" + o.size + "'");
  }
  s.width = w;
  s.height = h;
  if (!o.tile.empty()) {
    unsigned tw = 0, th = 0;
    char tx = 0, textra = 0;
    std::istringstream tile(o.tile);
    if (!(tile >> tw >> tx >> th) || (tx != 'x' && tx != 'X') || (tile >> textra) || tw == 0 || th == 0) {
      throw std::invalid_argument("--tile: expected WxH, got '" + o.tile + "'");
    }
    s.tileWidth = tw;
    s.tileHeight = th;
  }
  if (!o.envColor.empty()) {
    std::vector<float> c;
    std::stringstream ss(o.envColor);
    std::string part;
    while (std::getline(ss, part, ','))
      c.push_back(float(parseParam(params::kEnvColor, part, "--env-color")));
    if (c.size() != 3) {
      throw std::invalid_argument("--env-color: expected three non-negative numbers R,G,B, got '" +
                                  o.envColor + "'");
    }
    s.envColor = {c[0], c[1], c[2]};
  }
  if (o.sampler == "sobol") {
    s.sampler = render::SamplerKind::Sobol;
  } else if (o.sampler == "pcg") {
    s.sampler = render::SamplerKind::Pcg;
  } else {
    throw std::invalid_argument("--sampler: expected sobol or pcg, got '" + o.sampler + "'");
  }
  if (!(s.rrMin > 0.0f && s.rrMin <= s.rrMax && s.rrMax <= 1.0f)) {
    throw std::invalid_argument("--rr-min/--rr-max: need 0 < rr-min <= rr-max <= 1");
  }
  const auto mode = render::parseRenderMode(o.modeName);
  if (!mode)
    throw std::invalid_argument("--mode: expected pathtrace, hybrid or reflections, got '" + o.modeName +
                                "'");
  o.mode = *mode;
  o.hybrid.temporal = !o.noTemporal;
  s.defines.clear();
  for (const auto& d : o.defines) {
    const shader::Define def = shader::parseDefine(d, "--define");
    s.defines.emplace_back(def.name, def.value);
  }
  s.russianRoulette = !o.noRussianRoulette;
  s.nee = !o.noNee;
  s.mis = !o.noMis;
  s.aov = false;
  if (!o.aov.empty()) {
    std::stringstream ss(o.aov);
    std::string part;
    while (std::getline(ss, part, ',')) {
      if (part != "albedo" && part != "normal") {
        throw std::invalid_argument("--aov: expected albedo and/or normal, got '" + part + "'");
      }
      (part == "albedo" ? o.aovAlbedo : o.aovNormal) = true;
    }
    s.aov = true;
  }
}

}  // namespace wb::app
