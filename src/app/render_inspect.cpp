// `render --inspect-pixel X,Y [--inspect-samples N] --inspect-out FILE.json`: the path inspector headless.
#include "app/cmd_render.h"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "app/inspect_json.h"
#include "app/parameter_json.h"
#include "common/json_text.h"

namespace wb::app {
namespace {

// The vertex records one `render --inspect-out` keeps (the JSON document of all of them is built in memory
// before it is written), and what that costs at most, for the message.
constexpr uint32_t kMaxInspectVertexRecords = 1u << 15;
constexpr const char* kVertexRecordsCost = " vertex records: up to ~130 MB of JSON and ~0.7 GB of memory";

}  // namespace

void finishInspectFlags(RenderCommand& c) {
  const bool any = !c.inspectPixel.empty() || !c.inspectOut.empty() || c.inspectSamplesGiven;
  if (!any) {
    if (c.out.empty()) throw std::invalid_argument("--out: required (or --inspect-pixel with --inspect-out)");
    return;
  }
  if (c.inspectPixel.empty())
    throw std::invalid_argument("--inspect-pixel: required by the path inspector's flags");
  if (c.inspectOut.empty()) throw std::invalid_argument("--inspect-out: required with --inspect-pixel");
  unsigned x = 0, y = 0;
  char comma = 0, extra = 0;
  std::istringstream in(c.inspectPixel);
  if (c.inspectPixel.find_first_not_of("0123456789,") != std::string::npos || !(in >> x >> comma >> y) ||
      comma != ',' || (in >> extra)) {
    throw std::invalid_argument("--inspect-pixel: expected X,Y, got '" + c.inspectPixel + "'");
  }
  const auto& s = c.options.params.render;
  if (x >= s.width || y >= s.height) {
    throw std::invalid_argument("--inspect-pixel: " + c.inspectPixel + " is outside the " +
                                std::to_string(s.width) + "x" + std::to_string(s.height) + " image");
  }
  if (c.out.empty() && (!c.stats.empty() || !c.reference.empty() || !c.options.aov.empty()))
    throw std::invalid_argument("--stats, --reference and --aov describe an image: they need --out");
  if (std::filesystem::path(c.inspectOut).extension() != ".json")
    throw std::invalid_argument("--inspect-out must end in .json, got '" + c.inspectOut + "'");
  c.inspectX = x;
  c.inspectY = y;
  if (c.options.params.mode != render::RenderMode::PathTrace) {  // the hybrid modes' rays of the last frame
    if (c.inspectSamplesGiven)
      throw std::invalid_argument("--inspect-samples: the hybrid modes record the last frame's rays");
    return;
  }
  if (c.inspectSamplesGiven && c.inspectSamples == 0)
    throw std::invalid_argument("--inspect-samples: at least 1 (without the flag: --spp)");
  const std::string flag = c.inspectSamplesGiven ? "--inspect-samples" : "--inspect-samples (default: --spp)";
  if (!c.inspectSamplesGiven) c.inspectSamples = s.spp;
  if (c.inspectSamples > s.spp) {
    throw std::invalid_argument(flag + ": at most --spp (" + std::to_string(s.spp) + "), got " +
                                std::to_string(c.inspectSamples));
  }
  // Every record goes into one JSON document, built in memory before it is written: the records are bounded
  // by vertices, each sample taking up to max bounces + 1 of them.
  const uint32_t vertices = std::min(s.maxBounces + 1, render::kMaxInspectVertices);
  const uint32_t bound = std::min(render::kMaxInspectSamples, kMaxInspectVertexRecords / vertices);
  if (c.inspectSamples > bound) {
    throw std::invalid_argument(flag + ": at most " + std::to_string(bound) + " at --max-bounces " +
                                std::to_string(s.maxBounces) + " (a sample records up to " +
                                std::to_string(vertices) + " vertices and one inspection at most " +
                                std::to_string(kMaxInspectVertexRecords) + kVertexRecordsCost + "), got " +
                                std::to_string(c.inspectSamples));
  }
}

void startInspection(const RenderCommand& c, render::RenderSession& session) {
  if (auto* hybrid = session.hybrid()) {
    hybrid->setInspectPixel(glm::uvec2(c.inspectX, c.inspectY));
    return;
  }
  render::InspectRequest r;
  r.x = c.inspectX;
  r.y = c.inspectY;
  r.samples = c.inspectSamples;
  session.pathTracer().setInspection(r);
}

void writeInspection(const RenderCommand& c, render::RenderSession& session, uint32_t spp) {
  if (auto* hybrid = session.hybrid()) {
    InspectContext ctx;
    ctx.x = c.inspectX;
    ctx.y = c.inspectY;
    ctx.width = hybrid->settings().width;
    ctx.height = hybrid->settings().height;
    ctx.scene = session.scene().sourcePath.string();
    ctx.spp = spp;
    const auto out = hybrid->readOutput();
    const size_t i = (size_t(c.inspectY) * ctx.width + c.inspectX) * 4;
    ctx.pixelValue = glm::vec4(out[i], out[i + 1], out[i + 2], 1.0f);
    auto j = hybridInspectJson(ctx, hybrid->readInspection(), render::renderModeName(session.mode()));
    j["parameters"] = parametersJson(c.options.params);
    j["device"] = session.context().deviceName();
    writeJsonFile(c.inspectOut, j, "--inspect-out");
    std::printf("inspected pixel %u,%u of the last frame -> %s\n", c.inspectX, c.inspectY,
                c.inspectOut.c_str());
    return;
  }
  auto& tracer = session.pathTracer();
  const auto samples = render::inspectedSamples(tracer.readInspection());
  const auto accum = tracer.readAccumulation();
  const auto& s = tracer.settings();
  InspectContext ctx;
  ctx.x = c.inspectX;
  ctx.y = c.inspectY;
  ctx.width = s.width;
  ctx.height = s.height;
  ctx.samplesRequested = c.inspectSamples;
  ctx.scene = session.scene().sourcePath.string();
  const size_t i = (size_t(c.inspectY) * s.width + c.inspectX) * 4;
  ctx.pixelValue = glm::vec4(accum[i], accum[i + 1], accum[i + 2], accum[i + 3]);
  ctx.spp = spp;
  ctx.clock = tracer.clock();
  ctx.labels = tracer.debugLabels();
  auto j = inspectJson(ctx, samples);
  j["parameters"] = parametersJson(c.options.params);
  j["device"] = session.context().deviceName();
  writeJsonFile(c.inspectOut, j, "--inspect-out");
  std::printf("inspected pixel %u,%u: %zu samples -> %s\n", c.inspectX, c.inspectY, samples.size(),
              c.inspectOut.c_str());
}

int runInspectOnly(const RenderCommand& c, render::RenderSession& session) {
  startInspection(c, session);
  if (session.hybrid()) {  // a hybrid frame is the whole image
    session.render(c.options.params.render.spp);
    writeInspection(c, session, c.options.params.render.spp);
    return 0;
  }
  session.pathTracer().renderPixel(c.inspectX, c.inspectY, c.inspectSamples);
  writeInspection(c, session, c.inspectSamples);
  return 0;
}

}  // namespace wb::app
