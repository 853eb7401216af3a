#include "app/cmd_render.h"

#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "app/render_options.h"
#include "app/hybrid_json.h"
#include "app/render_session.h"
#include "common/file_io.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "eval/metrics.h"

namespace wb::app {
namespace {

std::filesystem::path aovPath(const std::filesystem::path& out, const std::string& name) {
  auto p = out;
  p.replace_filename(out.stem().string() + "." + name + out.extension().string());
  return p;
}

}  // namespace

int runRenderCommand(const std::vector<std::string>& args) {
  CLI::App cli("Render a scene headless and write the image", "workbench render");
  RenderOptions ro;
  std::string out, stats, reference;
  addRenderOptions(cli, ro);
  cli.add_option("--out", out, "output image (.png tonemapped, .exr linear)")->required();
  cli.add_option("--stats", stats, "write statistics as JSON");
  cli.add_option(
      "--reference", reference,
      "converged reference .exr of the same view: adds error_vs_reference (RMSE, relative MSE) to --stats");
  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());
    cli.parse(reversed);
    finishRenderOptions(ro);
  } catch (const CLI::CallForHelp&) {
    std::printf("%s", cli.help().c_str());
    return 0;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "workbench render: error: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "workbench render: error: %s\n", e.what());
    return 2;
  }
  const std::filesystem::path outPath(out);
  const std::string ext = outPath.extension().string();
  if (ext != ".png" && ext != ".exr") {
    std::fprintf(stderr, "workbench render: error: --out must end in .png or .exr, got '%s'\n", out.c_str());
    return 2;
  }
  try {
    // Every output is checked before the render: a render never ends in "cannot write" after the work.
    requireWritableFile(outPath, "--out");
    if (ro.aovAlbedo) requireWritableFile(aovPath(outPath, "albedo"), "--aov albedo");
    if (ro.aovNormal) requireWritableFile(aovPath(outPath, "normal"), "--aov normal");
    if (!stats.empty()) requireWritableFile(stats, "--stats");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench render: error: %s\n", e.what());
    return 2;
  }
  try {
    SessionOptions so;
    so.scenePath = ro.scene;
    so.settings = ro.settings;
    so.context.deviceName = ro.device;
    so.mode = ro.mode;
    so.hybrid = ro.hybrid;
    std::optional<eval::ImageRGBA> referenceImage;
    if (!reference.empty()) referenceImage = eval::readExr(reference);  // fail before the render
    RenderSession session(so);  // prints the scene's and environment's warnings
    const double seconds = session.render(ro.settings.spp);
    const auto image = session.image();
    eval::writeImage(outPath, image);
    if (ro.aovAlbedo) eval::writeImage(aovPath(outPath, "albedo"), session.aov(render::Aov::Albedo));
    if (ro.aovNormal) eval::writeImage(aovPath(outPath, "normal"), session.aov(render::Aov::Normal));
    const auto counters = session.pathTracer().readCounters();
    double mean[3] = {0, 0, 0};
    for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
      for (int c = 0; c < 3; ++c) mean[c] += image.pixels[4 * i + c];
    }
    const double pixels = double(image.width) * image.height;
    for (double& m : mean) m /= pixels;
    const double samples = pixels * ro.settings.spp;
    if (!stats.empty()) {
      nlohmann::json j;
      j["device"] = session.context().deviceName();
      j["driver"] = session.context().driverInfo();
      j["scene"] = session.scene().sourcePath.string();
      j["triangles"] = session.scene().triangleCount();
      j["width"] = image.width;
      j["height"] = image.height;
      j["size"] = std::to_string(image.width) + "x" + std::to_string(image.height);
      j["spp"] = ro.settings.spp;
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
      j["nan_inf_dropped"] = counters.droppedSamples;
      j["mean_rgb"] = {mean[0], mean[1], mean[2]};
      j["max_bounces"] = ro.settings.maxBounces;
      j["rr_start"] = ro.settings.rrStart;
      j["rr_min"] = ro.settings.rrMin;
      j["rr_max"] = ro.settings.rrMax;
      j["sampler"] = ro.sampler;
      j["seed"] = ro.settings.seed;
      const auto st = session.library().stats();
      j["shader_cache"] = {
          {"hits", st.hits}, {"misses", st.misses}, {"compiles", st.compiles}, {"compile_ms", st.compileMs}};
      j["blas_build_ms"] = session.gpuScene().accel().blasBuildMs();
      j["tlas_build_ms"] = session.gpuScene().accel().tlasBuildMs();
      j["device_bytes"] = session.gpuScene().deviceBytes();
      std::ofstream f(stats);
      f << jsonText(j, 2) << "\n";
      if (!f.flush()) throw std::runtime_error("cannot write --stats file '" + stats + "'");
    }
    // Said last: every file is written.
    std::printf("rendered %s (%u triangles) at %ux%u, %u spp in %.2f s on %s -> %s\n",
                session.scene().sourcePath.string().c_str(), unsigned(session.scene().triangleCount()),
                image.width, image.height, ro.settings.spp, seconds, session.context().deviceName().c_str(),
                outPath.string().c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench render: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app
