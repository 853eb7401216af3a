// `render --aov cost` and `render --asserts`: the path tracer's cost and asserts variants headless.
#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "app/cmd_render.h"
#include "app/debug_json.h"
#include "eval/cost_map.h"
#include "eval/image.h"

namespace wb::app {
namespace {

std::filesystem::path beside(const std::filesystem::path& out, const std::string& name,
                             const std::string& extension) {
  auto p = out;
  p.replace_filename(out.stem().string() + "." + name + extension);
  return p;
}

// How many failures are said on stderr (all of them go into --stats).
constexpr size_t kAssertsSaid = 10;

}  // namespace

void finishDebugFlags(const RenderCommand& c) {
  const bool pathTracer = c.options.params.mode == render::RenderMode::PathTrace;
  if (c.options.aovCost && !pathTracer)
    throw std::invalid_argument("--aov cost: the cost map is the path tracer's (--mode pathtrace)");
  if (c.asserts && !pathTracer)
    throw std::invalid_argument("--asserts: wbAssert is checked by the path tracer (--mode pathtrace)");
  if ((c.options.aovCost || c.asserts) && c.out.empty())
    throw std::invalid_argument(std::string(c.asserts ? "--asserts" : "--aov cost") +
                                ": writes beside the image: needs --out");
}

std::vector<std::filesystem::path> debugOutputs(const RenderCommand& c) {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path out(c.out);
  if (c.options.aovCost) files.push_back(beside(out, "cost", out.extension().string()));
  if (c.asserts) files.push_back(beside(out, "asserts", ".png"));
  return files;
}

void startDebugVariants(const RenderCommand& c, render::RenderSession& session) {
  if (!c.options.aovCost && !c.asserts) return;
  render::Instrumentation i;
  i.cost = c.options.aovCost;
  i.asserts = c.asserts;
  session.pathTracer().setInstrumentation(i);
  if (c.options.aovCost && !session.context().shaderClock().any())
    std::fprintf(stderr,
                 "warning: --aov cost: %s has no shader clock (VK_KHR_shader_clock%s): every cost reads 0\n",
                 session.context().deviceName().c_str(),
                 session.context().policy().shaderClock ? "" : ", or WB_SHADER_CLOCK=0");
}

uint32_t writeDebugOutputs(const RenderCommand& c, render::RenderSession& session, nlohmann::json& stats) {
  stats["pass_ms"] = passMsJson(session.renderer().passTimer());
  if (!c.options.aovCost && !c.asserts) return 0;
  auto& tracer = session.pathTracer();
  const auto& s = tracer.settings();
  const std::filesystem::path out(c.out);
  if (c.options.aovCost) {
    const auto cost = tracer.readAov(render::Aov::Cost);
    const eval::CostSummary summary = tracer.summarizeCost(cost);
    const auto file = beside(out, "cost", out.extension().string());
    if (out.extension() == ".exr") {
      eval::writeExr(file, {s.width, s.height, cost});  // means: r total, g trace, b shade; a the median
    } else {
      const auto perPixel = eval::pixelCosts(cost, s.width, s.height, summary.estimate);
      eval::writePng8(file, s.width, s.height, eval::heatMapRgba8(perPixel, summary.p95));
    }
    stats["cost"] = costJson(summary);
  }
  uint32_t failures = 0;
  if (c.asserts) {
    const render::AssertReport report = tracer.readAsserts();
    const auto labels = tracer.debugLabels();
    failures = report.failures;
    stats["asserts"] = assertsJson(report, labels);
    for (size_t i = 0; i < std::min(report.records.size(), kAssertsSaid); ++i) {
      const auto& r = report.records[i];
      std::fprintf(stderr, "assert failed: '%s' at pixel %u,%u sample %u bounce %s (%s)\n",
                   render::debugLabelText(r.label, labels).c_str(), r.pixel.x, r.pixel.y, r.sampleIndex,
                   r.bounce == WB_DEBUG_NO_BOUNCE ? "-" : std::to_string(r.bounce).c_str(),
                   render::debugStageName(r.stage));
    }
    if (report.failures > kAssertsSaid)
      std::fprintf(stderr, "... %u assert failures in all (%zu recorded)\n", report.failures,
                   report.records.size());
    // The image dimmed, the failing pixels recorded in magenta.
    const auto image = session.image();
    auto rgba =
        eval::tonemapToSrgb8(image, c.options.params.display.exposure, c.options.params.display.tonemap);
    for (size_t i = 0; i < rgba.size(); i += 4)
      for (int k = 0; k < 3; ++k) rgba[i + k] = uint8_t(rgba[i + k] / 4);
    for (const auto& r : report.records) {
      if (r.pixel.x >= s.width || r.pixel.y >= s.height) continue;
      const size_t i = (size_t(r.pixel.y) * s.width + r.pixel.x) * 4;
      rgba[i] = 255;
      rgba[i + 1] = 0;
      rgba[i + 2] = 255;
    }
    eval::writePng8(beside(out, "asserts", ".png"), s.width, s.height, rgba);
  }
  return failures;
}

}  // namespace wb::app
