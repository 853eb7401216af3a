#include "app/render_options.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "common/numbers.h"
#include "shader/types.h"

namespace wb::app {

void addRenderOptions(CLI::App& app, RenderOptions& o) {
  app.add_option("scene", o.scene, "glTF scene (.gltf/.glb); default: assets/default_scene.gltf");
  app.add_option("--size", o.size, "image size WxH")->capture_default_str();
  app.add_option("--aov", o.aov,
                 "write AOVs beside --out: albedo, normal, cost (the shader clock per sample, path tracer)");
  app.add_option("--device", o.device, "Vulkan device name (substring)");
  app.add_option("--tile", o.tile, "trace each sample in tiles of WxH (dispatch-shape experiments)");
  app.add_option("--samples-per-launch", o.samplesPerLaunch,
                 "samples one ray tracing launch traces, 0 to 64 (default 0: the device's choice, enough to "
                 "fill a GPU at small sizes, 1 on a CPU device)");
  app.add_option("--define", o.defines,
                 "preprocessor define K=V (or K) for the path tracer's shaders; repeatable");
  o.flags.addTo(app, o.params);
}

void finishRenderOptions(RenderOptions& o) {
  o.flags.apply(o.params);
  auto& s = o.params.render;
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
  if (!o.samplesPerLaunch.empty()) {
    const auto n = parseDecimalUnsigned(o.samplesPerLaunch);
    if (!n || *n > 64)
      throw std::invalid_argument("--samples-per-launch: expected 0 to 64, got '" + o.samplesPerLaunch + "'");
    s.samplesPerLaunch = uint32_t(*n);
  }
  s.defines.clear();
  for (const auto& d : o.defines) {
    const shader::Define def = shader::parseDefine(d, "--define");
    s.defines.emplace_back(def.name, def.value);
  }
  s.aov = false;
  if (!o.aov.empty()) {
    std::stringstream ss(o.aov);
    std::string part;
    while (std::getline(ss, part, ',')) {
      if (part != "albedo" && part != "normal" && part != "cost") {
        throw std::invalid_argument("--aov: expected albedo, normal and/or cost, got '" + part + "'");
      }
      (part == "albedo" ? o.aovAlbedo : part == "normal" ? o.aovNormal : o.aovCost) = true;
    }
    s.aov = true;
  }
}

}  // namespace wb::app
