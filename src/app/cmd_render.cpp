#include "app/cmd_render.h"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "app/render_options.h"
#include "app/hybrid_json.h"
#include "app/parameter_json.h"
#include "app/progress.h"
#include "common/file_io.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "eval/metrics.h"
#include "render/render_session.h"

namespace wb::app {
namespace {

std::filesystem::path aovPath(const std::filesystem::path& out, const std::string& name) {
  auto p = out;
  p.replace_filename(out.stem().string() + "." + name + out.extension().string());
  return p;
}

}  // namespace

void RenderCommand::addFlags(CLI::App& cli) {
  addRenderOptions(cli, options);
  cli.add_option("--out", out, "output image (.png tonemapped, .exr linear); required unless --inspect-out");
  cli.add_option("--stats", stats, "write statistics as JSON");
  cli.add_option(
      "--reference", reference,
      "converged reference .exr of the same view: adds error_vs_reference (RMSE, relative MSE) to --stats");
  cli.add_option("--inspect-pixel", inspectPixel,
                 "path inspector: record the paths of pixel X,Y (0,0 = top left)");
  inspectSamplesOption = cli.add_option(
      "--inspect-samples", inspectSamples,
      "path inspector: samples to record (default: --spp; at most --spp, and as many as 32768 vertex records "
      "hold at --max-bounces; without --out only the pixel is traced)");
  cli.add_option("--inspect-out", inspectOut,
                 "path inspector: write the records as JSON (docs/path_inspector.md)");
  cli.add_flag("--asserts", asserts,
               "check wbAssert at every pixel (the path tracer's asserts variant): failures on stderr, in "
               "--stats and marked in OUT.asserts.png; exit status 1 when one failed (docs/cost.md)");
}

void RenderCommand::finish() {
  finishRenderOptions(options);
  if (options.params.render.spp == 0) throw std::invalid_argument("--spp: at least 1 sample per pixel");
  inspectSamplesGiven = inspectSamplesOption && inspectSamplesOption->count() > 0;
  finishInspectFlags(*this);
  finishDebugFlags(*this);
  const std::string ext = std::filesystem::path(out).extension().string();
  if (!out.empty() && ext != ".png" && ext != ".exr")
    throw std::invalid_argument("--out must end in .png or .exr, got '" + out + "'");
}

int runRenderCommand(const std::vector<std::string>& args) {
  RenderCommand c;
  return runCommand(c, args);
}

int RenderCommand::run() {
  const RenderOptions& ro = options;
  const std::filesystem::path outPath(out);
  try {
    // Every output is checked before the render: a render never ends in "cannot write" after the work.
    if (!out.empty()) requireWritableFile(outPath, "--out");
    if (!inspectOut.empty()) requireWritableFile(inspectOut, "--inspect-out");
    if (ro.aovAlbedo) requireWritableFile(aovPath(outPath, "albedo"), "--aov albedo");
    if (ro.aovNormal) requireWritableFile(aovPath(outPath, "normal"), "--aov normal");
    if (!stats.empty()) requireWritableFile(stats, "--stats");
    for (const auto& f : debugOutputs(*this)) requireWritableFile(f, asserts ? "--asserts" : "--aov cost");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench render: error: %s\n", e.what());
    return 2;
  }
  try {
    render::SessionOptions so;
    so.scenePath = ro.scene;
    so.settings = ro.params.render;
    so.context.deviceName = ro.device;
    so.mode = ro.params.mode;
    so.hybrid = ro.params.hybrid;
    std::optional<eval::ImageRGBA> referenceImage;
    if (!reference.empty()) referenceImage = eval::readExr(reference);  // fail before the render
    render::RenderSession session(so);  // prints the scene's and environment's warnings
    if (!inspectOut.empty() && out.empty()) return runInspectOnly(*this, session);
    if (!inspectOut.empty()) startInspection(*this, session);
    startDebugVariants(*this, session);
    // Ctrl-C stops after the sample in progress; what was accumulated is written, marked partial.
    InterruptRequest interrupt;
    ProgressLine progress("render");
    const uint32_t total = ro.params.render.spp;
    double last = 0;
    const double seconds = session.render(total, [&](uint32_t done, double elapsed) {
      interrupt.noteWorkSeconds(elapsed - last);  // a signal's grace covers a sample in progress
      last = elapsed;
      progress.update("", double(done) / double(total),
                      std::to_string(done) + "/" + std::to_string(total) + " spp");
      return !interrupt.requested();
    });
    progress.finish();
    const uint32_t spp = uint32_t(session.frameSeconds().size());
    const bool partial = spp < ro.params.render.spp;
    if (spp == 0) throw std::runtime_error("interrupted before the first sample finished: nothing written");
    if (!inspectOut.empty()) writeInspection(*this, session, spp);
    const auto image = session.image();
    eval::writeImage(outPath, image, ro.params.display.exposure, ro.params.display.tonemap);
    if (ro.aovAlbedo) eval::writeImage(aovPath(outPath, "albedo"), session.aov(render::Aov::Albedo));
    if (ro.aovNormal) eval::writeImage(aovPath(outPath, "normal"), session.aov(render::Aov::Normal));
    const auto counters = session.renderer().readCounters();
    double mean[3] = {0, 0, 0};
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
      for (int c = 0; c < 3; ++c) mean[c] += image.pixels[4 * i + c];
    }
    const double pixels = double(image.width) * image.height;
    for (double& m : mean) m /= pixels;
    const double samples = pixels * spp;
    nlohmann::json j;
    const uint32_t assertFailures = writeDebugOutputs(*this, session, j);  // cost map, asserts, pass_ms
    if (!stats.empty()) {
      j["device"] = session.context().deviceName();
      j["driver"] = session.context().driverInfo();
      j["scene"] = session.scene().sourcePath.string();
      j["triangles"] = session.scene().triangleCount();
      j["width"] = image.width;
      j["height"] = image.height;
      j["size"] = std::to_string(image.width) + "x" + std::to_string(image.height);
      j["spp"] = spp;  // samples rendered (fewer than asked when interrupted)
      j["spp_requested"] = ro.params.render.spp;
      j["partial"] = partial;
      j["mode"] = render::renderModeName(session.mode());
      const auto& frames = session.frameSeconds();
      j["frames"] = frames.size();
      j["seconds_per_frame"] = frames.empty() ? 0.0 : seconds / double(frames.size());
      j["frame_seconds"] = frames;
      if (frames.size() > 1) {
        double rest = 0;
        for (size_t i = 1; i < frames.size(); ++i) rest += frames[i];
        j["seconds_per_frame_after_first"] = rest / double(frames.size() - 1);
      }
      if (auto* hybrid = session.hybrid()) j["hybrid"] = hybridSettingsJson(*hybrid);
      if (referenceImage) {
        eval::requireSameSize(image, *referenceImage, "--reference");
        j["error_vs_reference"] = {{"reference", reference},
                                   {"rmse", eval::rmse(image, *referenceImage)},
                                   {"rel_mse", eval::relMse(image, *referenceImage, 0.01)},
                                   {"rel_mse_eps", 0.01}};
      }
      j["seconds"] = seconds;
      j["setup_seconds"] = session.setupSeconds();
      j["samples_per_second"] = samples / seconds;
      j["paths_per_second"] = counters.pathCount / seconds;
      j["rays_per_second"] = counters.rayCount / seconds;
      j["rays"] = counters.rayCount;
      j["shadow_rays"] = counters.shadowRayCount;
      // The shadow rays in a launch of their own (DevicePolicy::splitShadows).
      j["split_shadows"] = session.pathTracer().splitsShadows();
      // Shader execution reordering: what the device offers, and whether the path rays used it.
      j["invocation_reorder"] = session.context().invocationReorderSupport();
      j["invocation_reorder_used"] = session.pathTracer().reordersInvocations();
      j["nan_inf_dropped"] = counters.droppedSamples;
      j["mean_rgb"] = {mean[0], mean[1], mean[2]};
      j["max_bounces"] = ro.params.render.maxBounces;
      j["rr_start"] = ro.params.render.rrStart;
      j["rr_min"] = ro.params.render.rrMin;
      j["rr_max"] = ro.params.render.rrMax;
      j["rr_exponent"] = ro.params.render.rrExponent;
      j["sampler"] = render::samplerNames().at(size_t(ro.params.render.sampler));
      j["seed"] = ro.params.render.seed;
      j["parameters"] = parametersJson(ro.params);  // every parameter, the schema of every JSON writer
      const auto st = session.library().stats();
      j["shader_cache"] = {
          {"hits", st.hits}, {"misses", st.misses}, {"compiles", st.compiles}, {"compile_ms", st.compileMs}};
      j["blas_build_ms"] = session.gpuScene().accel().blasBuildMs();
      j["tlas_build_ms"] = session.gpuScene().accel().tlasBuildMs();
      j["device_bytes"] = session.gpuScene().deviceBytes();
      writeJsonFile(stats, j, "--stats");
    }
    // Said last: every file is written.
    std::printf("%s %s (%u triangles) at %ux%u, %u spp in %.2f s on %s -> %s\n",
                partial ? "interrupted: partial render of" : "rendered",
                session.scene().sourcePath.string().c_str(), unsigned(session.scene().triangleCount()),
                image.width, image.height, spp, seconds, session.context().deviceName().c_str(),
                outPath.string().c_str());
    if (partial) {
      std::printf("workbench render: %u of %u spp were rendered before the interrupt\n", spp,
                  ro.params.render.spp);
      return 128 + interrupt.signal();
    }
    if (assertFailures > 0) {
      std::fprintf(stderr, "workbench render: %u wbAssert failures\n", assertFailures);
      return 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench render: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app
