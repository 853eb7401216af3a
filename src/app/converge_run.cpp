#include "app/converge_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>

#include "eval/metrics.h"

namespace wb::app {

std::vector<std::string> splitFlags(const std::string& text, const std::string& what) {
  std::vector<std::string> out;
  std::string cur;
  char quote = 0;
  bool any = false;
  for (char c : text) {
    if (quote) {
      if (c == quote) {
        quote = 0;
      } else {
        cur += c;
      }
    } else if (c == '"' || c == '\'') {
      quote = c;
      any = true;
    } else if (c == ' ' || c == '\t') {
      if (!cur.empty() || any) out.push_back(cur);
      cur.clear();
      any = false;
    } else {
      cur += c;
    }
  }
  if (quote) throw std::invalid_argument(what + ": unbalanced quote in '" + text + "'");
  if (!cur.empty() || any) out.push_back(cur);
  return out;
}

RenderOptions parseRenderFlags(const std::vector<std::string>& args,
                               const std::function<void(CLI::App&)>& ignored) {
  CLI::App cli;
  cli.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  RenderOptions ro;
  addRenderOptions(cli, ro);
  if (ignored) ignored(cli);
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  cli.parse(reversed);
  finishRenderOptions(ro);
  return ro;
}

render::SessionOptions sessionOptions(const RenderOptions& ro) {
  render::SessionOptions so;
  so.scenePath = ro.scene;
  so.settings = ro.params.render;
  so.context.deviceName = ro.device;
  so.quiet = true;
  so.mode = ro.params.mode;
  so.hybrid = ro.params.hybrid;
  return so;
}

uint32_t runSeed(uint32_t base, uint32_t run) {
  return base + 1 + run * 7919u;
}

double timedRender(render::RenderSession& session, uint32_t samples) {
  const auto t0 = std::chrono::steady_clock::now();
  session.renderer().render(samples);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

render::Parameters referenceParameters(const render::Parameters& base) {
  render::Parameters p = base;
  p.render.seed = kReferenceSeed;
  p.render.denoise = false;  // a reference is the estimator's own image
  p.mode = render::RenderMode::PathTrace;
  return p;
}

ReferenceRender renderReference(const RenderOptions& base, uint32_t spp, ProgressLine& progress,
                                const std::function<bool()>& stop) {
  RenderOptions ro = base;
  ro.params = referenceParameters(base.params);
  render::RenderSession session(sessionOptions(ro));
  session.renderer().resetAccumulation();
  ReferenceRender out;
  out.setupSeconds = session.setupSeconds();
  out.device = session.context().deviceName();
  for (uint32_t done = 0; done < spp;) {
    if (stop && stop()) {
      progress.finish();
      out.interrupted = true;
      return out;
    }
    const uint32_t n = std::min<uint32_t>(8, spp - done);
    out.seconds += timedRender(session, n);
    done += n;
    char detail[96];
    std::snprintf(detail, sizeof detail, "%u/%u spp", done, spp);
    progress.update("reference", double(done) / spp, detail, done == spp);
  }
  progress.finish();
  out.image = session.image();
  return out;
}

eval::ImageRGBA readReferenceFile(const std::string& path, uint32_t width, uint32_t height) {
  eval::ImageRGBA ref;
  try {
    ref = eval::readExr(path);
  } catch (const std::exception& e) {
    throw std::invalid_argument(std::string("--reference: ") + e.what());
  }
  const bool same = ref.width == width && ref.height == height;
  const bool multiple =
      ref.width % width == 0 && ref.height % height == 0 && ref.width / width == ref.height / height;
  if (!same && !multiple) {
    throw std::invalid_argument(
        "--reference '" + path + "' is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
        ", the render " + std::to_string(width) + "x" + std::to_string(height) +
        ": a reference is the render's size or the same integer multiple of it on both "
        "axes (it is box-downsampled)");
  }
  return ref;
}

eval::ImageRGBA downsampleReference(eval::ImageRGBA ref, const std::string& path, uint32_t width,
                                    uint32_t height, std::string& description) {
  description = "file `" + path + "`";
  if (ref.width != width || ref.height != height) {
    ref = eval::downsampleTo(ref, width, height);
    description += " (box-downsampled to " + std::to_string(width) + "x" + std::to_string(height) + ")";
  }
  return ref;
}

eval::ImageRGBA loadReferenceFile(const std::string& path, uint32_t width, uint32_t height,
                                  std::string& description) {
  return downsampleReference(readReferenceFile(path, width, height), path, width, height, description);
}

void addMeasurement(Checkpoint& cp, eval::ImageRGBA image, const eval::ImageRGBA& reference, double seconds) {
  cp.seconds.push_back(seconds);
  cp.mse.push_back(eval::mse(image, reference));
  cp.relMse.push_back(eval::relMse(image, reference, 0.01));
  cp.mean.push_back(eval::meanRgb(image));
  cp.images.push_back(std::move(image));
}

}  // namespace wb::app
