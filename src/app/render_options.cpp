#include "app/render_options.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

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
  app.add_option("--rr-min", s.rrMin, "lowest Russian roulette survival probability")->capture_default_str();
  app.add_option("--rr-max", s.rrMax, "highest Russian roulette survival probability")->capture_default_str();
  app.add_flag("--no-rr", o.noRussianRoulette, "disable Russian roulette");
  app.add_flag("--no-nee", o.noNee, "disable next-event estimation (BRDF sampling only)");
  app.add_flag("--no-mis", o.noMis, "environment by light sampling only (no MIS with BRDF sampling)");
  app.add_option("--sampler", o.sampler, "sobol|pcg")->capture_default_str();
  app.add_option("--seed", s.seed, "random seed")->capture_default_str();
  app.add_option("--env", s.envPath, "equirectangular .hdr environment map");
  app.add_option("--env-color", o.envColor, "constant environment radiance R,G,B");
  app.add_option("--env-rotation", s.envRotationDeg, "environment rotation about +Y, degrees")
      ->capture_default_str();
  app.add_option("--env-intensity", s.envIntensity, "environment intensity multiplier")
      ->capture_default_str();
  app.add_option("--aov", o.aov, "write AOVs: albedo,normal (beside --out)");
  app.add_option("--device", o.device, "Vulkan device name (substring)");
  app.add_flag("--generic", s.generic, "all-features shaders instead of the scene-specialised build");
}

static float parseFloat(const std::string& text, const std::string& what) {
  size_t used = 0;
  float v = 0;
  try {
    v = std::stof(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v))
    throw std::invalid_argument(what + ": '" + text + "' is not a number");
  return v;
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
  if (!o.envColor.empty()) {
    std::vector<float> c;
    std::stringstream ss(o.envColor);
    std::string part;
    while (std::getline(ss, part, ',')) c.push_back(parseFloat(part, "--env-color"));
    if (c.size() != 3 || c[0] < 0 || c[1] < 0 || c[2] < 0) {
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
  if (!std::isfinite(s.envIntensity) || s.envIntensity < 0) {
    throw std::invalid_argument("--env-intensity: must be a non-negative number");
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
    }
    s.aov = true;
  }
}

}  // namespace wb::app
