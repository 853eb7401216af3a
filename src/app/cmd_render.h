// `workbench render [SCENE] --size WxH --spp N --out FILE.png|FILE.exr [--stats FILE.json] ...`: a headless
// render to an image file; with --inspect-pixel X,Y --inspect-out FILE.json also (or, without --out, only)
// the path inspector's records of that pixel's samples.
#pragma once
#include <string>
#include <vector>

#include "app/command.h"
#include "app/render_options.h"

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
};

int runRenderCommand(const std::vector<std::string>& args);

}  // namespace wb::app
