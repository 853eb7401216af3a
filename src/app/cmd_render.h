// `workbench render [SCENE] --size WxH --spp N --out FILE.png|FILE.exr [--stats FILE.json] ...`: a headless
// render to an image file; with --inspect-pixel X,Y --inspect-out FILE.json also (or, without --out, only)
// the path inspector's records of that pixel's samples.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/command.h"
#include "app/render_options.h"
#include "render/render_session.h"

namespace wb::app {

class RenderCommand : public Command {
 public:
  const char* name() const override { return "render"; }
  const char* description() const override { return "Render a scene headless and write the image"; }
  void addFlags(CLI::App& app) override;
  void finish() override;
  int run() override;

  RenderOptions options;
  std::string out, stats, reference;
  // The path inspector (--inspect-pixel X,Y --inspect-out FILE.json [--inspect-samples N]).
  std::string inspectPixel, inspectOut;
  uint32_t inspectSamples = 0;  // 0: not given (--spp)
  bool inspectSamplesGiven = false;
  CLI::Option* inspectSamplesOption = nullptr;
  uint32_t inspectX = 0, inspectY = 0;
  bool asserts = false;  // --asserts: the path tracer's asserts variant
};

int runRenderCommand(const std::vector<std::string>& args);

// The path inspector headless (render_inspect.cpp): with --out the image is rendered as usual by the
// inspecting variant (the same image) and the first N samples of the pixel are recorded; without it only the
// pixel is traced, N samples.
// Parses --inspect-pixel and checks the inspector's flags against the rest; throws std::invalid_argument.
void finishInspectFlags(RenderCommand& c);
// Switches the session's path tracer to the inspecting variant for the command's pixel and samples.
void startInspection(const RenderCommand& c, render::RenderSession& session);
// Writes --inspect-out from the records of the last render (`spp` samples traced for the pixel).
void writeInspection(const RenderCommand& c, render::RenderSession& session, uint32_t spp);
// Without --out: traces the pixel alone and writes --inspect-out. Returns the exit status.
int runInspectOnly(const RenderCommand& c, render::RenderSession& session);

// The cost and asserts variants (render_debug.cpp): `--aov cost` writes the cost map beside --out
// (OUT.cost.png a heat map, OUT.cost.exr the clocks) and `cost` into --stats; `--asserts` checks wbAssert at
// every pixel, says the first failures on stderr, writes OUT.asserts.png (the image with failing pixels
// marked) and `asserts` into --stats. Refuses them outside the path tracer; throws std::invalid_argument
// naming the flag.
void finishDebugFlags(const RenderCommand& c);
// Switches the session's path tracer to the variants the flags ask for.
void startDebugVariants(const RenderCommand& c, render::RenderSession& session);
// The files the variants write (checked before the render).
std::vector<std::filesystem::path> debugOutputs(const RenderCommand& c);
// After the render: writes the cost map and the marked image, adds `cost`, `asserts` and `pass_ms` (GPU ms
// per sample, the median) to `stats`. Returns the asserts' failures (0 without --asserts).
uint32_t writeDebugOutputs(const RenderCommand& c, render::RenderSession& session, nlohmann::json& stats);

}  // namespace wb::app
