#include "app/cmd_bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <sys/resource.h>
#include <sys/utsname.h>

#include <CLI/CLI.hpp>

#include "app/bench_cost.h"
#include "app/bench_denoise.h"
#include "app/bench_roofline.h"
#include "app/bench_window.h"
#include "app/debug_json.h"
#include "app/process.h"
#include "app/progress.h"
#include "common/env.h"
#include "common/file_io.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "common/statistics.h"
#include "eval/metrics.h"
#include "scene/procedural.h"
#include "shader/hash.h"
#include "render/render_session.h"
#include "vk/driver_policy.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace wb::app {
namespace {

json machineInfo() {
  json m;
  std::ifstream cpu("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpu, line)) {
    if (line.rfind("model name", 0) == 0) {
      m["cpu"] = line.substr(line.find(':') + 2);
      break;
    }
  }
  m["cores"] = std::thread::hardware_concurrency();
  utsname u{};
  if (uname(&u) == 0) m["kernel"] = std::string(u.sysname) + " " + u.release;
  std::ifstream os("/etc/os-release");
  while (std::getline(os, line)) {
    if (line.rfind("PRETTY_NAME=", 0) == 0) m["os"] = line.substr(13, line.size() - 14);
  }
  return m;
}

std::string isoDate() {
  std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

double peakRssMb() {
  rusage r{};
  getrusage(RUSAGE_SELF, &r);
  return double(r.ru_maxrss) / 1024.0;
}

struct BenchScene {
  std::string name;
  std::string path;  // empty: sceneData
  std::optional<scene::Scene> data;
};

// A session on a bench scene at a size, in a mode, on the chosen device.
render::SessionOptions benchSession(const BenchScene& bs, uint32_t w, uint32_t h, const std::string& device,
                                    render::RenderMode mode = render::RenderMode::PathTrace) {
  render::SessionOptions o;
  o.scenePath = bs.path;
  o.sceneData = bs.data;
  o.settings.width = w;
  o.settings.height = h;
  o.context.deviceName = device;
  o.mode = mode;
  o.quiet = true;
  return o;
}

// Path tracer rates of one scene and variant: medians over `repeats` runs of `spp` samples after a warm-up;
// the specialised variant also gets the roofline (bench_roofline.h).
json benchPathTracer(const BenchScene& bs, bool generic, uint32_t w, uint32_t h, uint32_t spp, int repeats,
                     const std::string& device, std::string& deviceName, std::string& driver,
                     bool* cpuDevice = nullptr) {
  render::SessionOptions o = benchSession(bs, w, h, device);
  o.settings.generic = generic;
  render::RenderSession s(o);
  deviceName = s.context().deviceName();
  driver = s.context().driverInfo();
  s.render(1);  // warm-up: the driver compiles the pipeline at its first trace
  std::vector<double> paths, rays, primary, bounce, shadow, seconds;
  for (int r = 0; r < repeats; ++r) {
    const double t = s.render(spp);
    const auto c = s.renderer().readCounters();
    seconds.push_back(t);
    paths.push_back(c.pathCount / t);
    rays.push_back(c.rayCount / t);
    primary.push_back(c.pathCount / t);  // one camera ray per path
    shadow.push_back(c.shadowRayCount / t);
    bounce.push_back((double(c.rayCount) - c.pathCount - c.shadowRayCount) / t);
  }
  json j;
  j["features"] = scene::describeFeatures(s.pathTracer().features());
  j["seconds_per_sample"] = median(seconds) / spp;
  j["paths_per_second"] = median(paths);
  j["rays_per_second"] = median(rays);
  j["primary_rays_per_second"] = median(primary);
  j["bounce_rays_per_second"] = median(bounce);
  j["shadow_rays_per_second"] = median(shadow);
  j["triangles"] = s.scene().triangleCount();
  j["blas_build_ms"] = s.gpuScene().accel().blasBuildMs();
  j["tlas_build_ms"] = s.gpuScene().accel().tlasBuildMs();
  j["scene_device_bytes"] = s.gpuScene().deviceBytes();
  j["pass_ms"] = passMsJson(s.renderer().passTimer());  // GPU ms per sample, the last run's
  j["split_shadows"] = s.pathTracer().splitsShadows();
  j["invocation_reorder"] = s.context().invocationReorderSupport();
  j["invocation_reorder_used"] = s.pathTracer().reordersInvocations();
  if (!generic) j.update(benchRoofline(s, repeats));
  if (cpuDevice) *cpuDevice = s.context().policy().compilesAtFirstDispatch;
  return j;
}

// Cold and warm start to the first frame, as a user runs it: a new process each time.
json benchStartup(int repeats, const fs::path& work) {
  std::vector<double> coldMs, warmMs, coldCompiles, warmCompiles;
  for (int r = 0; r < repeats; ++r) {
    const fs::path cache = work / ("cache" + std::to_string(r));
    fs::remove_all(cache);
    fs::create_directories(cache);
    const std::map<std::string, std::string> env = {{"WB_SHADER_CACHE_DIR", cache.string()},
                                                    {"MESA_SHADER_CACHE_DIR", (cache / "mesa").string()}};
    for (int pass = 0; pass < 2; ++pass) {
      const fs::path stats = work / "startup.json";
      auto start = std::chrono::steady_clock::now();
      auto child = ChildProcess::spawn(selfExecutable(),
                                       {"render", "--size", "64x64", "--spp", "1", "--out",
                                        (work / "s.png").string(), "--stats", stats.string()},
                                       env, (work / "startup.log").string());
      const int rc = child.wait();
      const double total =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      if (rc != 0) throw std::runtime_error("start-up run failed: " + readText(work / "startup.log"));
      const auto j = json::parse(readText(stats));
      (pass == 0 ? coldMs : warmMs).push_back(total);
      (pass == 0 ? coldCompiles : warmCompiles).push_back(j["shader_cache"]["compiles"].get<double>());
    }
  }
  return {{"cold_to_first_frame_ms", median(coldMs)},
          {"warm_to_first_frame_ms", median(warmMs)},
          {"cold_glslang_compiles", median(coldCompiles)},
          {"warm_glslang_compiles", median(warmCompiles)},
          {"what",
           "new process, render of the default scene at 64x64, 1 spp, to the written image; cold = empty "
           "SPIR-V and Mesa caches"}};
}

// Edits of the closest-hit shader while `watch` renders: edit-to-new-pipeline and edit-to-first-frame.
std::string envOr(const char* name) {
  return env::get(name).value_or("");
}

// ownMesaCache: the bench process's MESA_SHADER_CACHE_DIR is the workbench's (not the user's): the child then
// gets its own under its fresh shader cache, or the deterministic edits would hit the pipelines of earlier
// runs.
json benchHotReload(int edits, const std::string& size, const fs::path& work, bool ownMesaCache) {
  const fs::path root = work / "root";
  fs::remove_all(root);
  fs::create_directories(root / "shader_cache");
  fs::copy(shaderDir(), root / "shaders", fs::copy_options::recursive);
  fs::copy(assetDir(), root / "assets", fs::copy_options::recursive);
  const fs::path log = work / "reloads.jsonl", out = work / "watch.log";
  fs::remove(log);
  auto child = ChildProcess::spawn(
      selfExecutable(), {"watch", "--headless", "--size", size, "--seconds", "600", "--log", log.string()},
      {{"WB_ROOT", root.string()},
       {"WB_SHADER_CACHE_DIR", (root / "shader_cache").string()},
       {"MESA_SHADER_CACHE_DIR", ownMesaCache ? "" : envOr("MESA_SHADER_CACHE_DIR")}},
      out.string());
  auto waitFor = [&](auto pred, double seconds) {
    auto start = std::chrono::steady_clock::now();
    while (!pred()) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > seconds)
        return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
  };
  auto logLines = [&] {
    std::vector<json> v;
    std::ifstream f(log);
    std::string line;
    while (std::getline(f, line)) {
      if (!line.empty()) v.push_back(json::parse(line));
    }
    return v;
  };
  if (!waitFor([&] { return readText(out).find("watching") != std::string::npos; }, 60)) {
    child.terminate();
    throw std::runtime_error("watch did not start: " + readText(out));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(3000));  // past the first frames (they compile)
  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  const std::string original = readText(chit);
  std::vector<double> toPipeline, toFrame, frameBefore, frameDuring, firstFrame, compileMs, pipelineMs,
      libraryMs, linkMs, librariesCompiled, slowest, control;
  for (int i = 0; i < edits; ++i) {
    // Saved in place, as an editor that rewrites the file does (what the reload measurement times).
    std::ofstream(chit, std::ios::trunc) << closestHitEdit(original, i);
    if (!waitFor([&] { return logLines().size() >= size_t(i + 1); }, 60)) break;
    const auto e = logLines()[i];
    if (!e["ok"].get<bool>()) continue;
    toPipeline.push_back(e["edit_to_new_pipeline_ms"].get<double>());
    if (e["edit_to_first_frame_ms"].is_number()) toFrame.push_back(e["edit_to_first_frame_ms"].get<double>());
    frameBefore.push_back(e["frame_ms_median_before"].get<double>());
    frameDuring.push_back(e["frame_ms_max_during_rebuild"].get<double>());
    firstFrame.push_back(e["first_new_frame_ms"].get<double>());
    compileMs.push_back(e["compile_ms"].get<double>());
    pipelineMs.push_back(e["pipeline_ms"].get<double>());
    libraryMs.push_back(e["pipeline_library_ms"].get<double>());
    linkMs.push_back(e["pipeline_link_ms"].get<double>());
    librariesCompiled.push_back(e["pipeline_libraries_compiled"].get<double>());
    // The slowest frame from the edit to the first frame with the new pipeline (included: it carries any
    // compile the driver left for the first dispatch), relative to the frames before the edit.
    if (frameBefore.back() > 0) {
      slowest.push_back(std::max(frameDuring.back(), firstFrame.back()) / frameBefore.back());
      control.push_back(e["frame_ms_max_before_same_span"].get<double>() / frameBefore.back());
    }
    // Longer than a rebuild: the next edit's control span (see watch) holds no frame of this one's.
    std::this_thread::sleep_for(std::chrono::milliseconds(2000));
  }
  child.terminate();
  return {{"edits", toPipeline.size()},
          {"trace_size", size},
          {"edit_to_new_pipeline_ms_p50", percentile(toPipeline, 0.5)},
          {"edit_to_new_pipeline_ms_p95", percentile(toPipeline, 0.95)},
          {"edit_to_first_frame_ms_p50", percentile(toFrame, 0.5)},
          {"edit_to_first_frame_ms_p95", percentile(toFrame, 0.95)},
          {"frame_ms_median_before_edit", median(frameBefore)},
          {"frame_ms_max_during_rebuild_median", median(frameDuring)},
          {"first_new_frame_ms_median", median(firstFrame)},
          {"first_new_frame_ms_p95", percentile(firstFrame, 0.95)},
          {"compile_ms_median", median(compileMs)},
          {"pipeline_ms_median", median(pipelineMs)},
          // Linked pipelines (GPUs; 0 when monolithic): libraries compiled per edit, the compile, the link.
          {"pipeline_libraries_compiled_median", median(librariesCompiled)},
          {"pipeline_library_ms_median", median(libraryMs)},
          {"pipeline_link_ms_median", median(linkMs)},
          {"slowest_frame_vs_before_p50", percentile(slowest, 0.5)},
          {"slowest_frame_vs_before_max", percentile(slowest, 1.0)},
          {"slowest_frame_vs_before_per_edit", slowest},
          // The same ratio for the slowest frame of as long a span just before each edit: the noise floor.
          {"control_slowest_frame_vs_before_p50", percentile(control, 0.5)},
          {"control_slowest_frame_vs_before_max", percentile(control, 1.0)}};
}

// Speed against error of the three modes: time per frame, and the error against a converged path-traced
// reference of the same view after 1 frame and after `frames` frames (hybrid modes accumulate their shadows
// and AO over frames; the path tracer accumulates samples). The reference is cached in
// shader_cache/references/ (keyed by scene, its mtime, size and spp).
json benchModes(const std::vector<BenchScene>& scenes, uint32_t w, uint32_t h, uint32_t refSpp,
                uint32_t frames, const std::string& speedSize, int repeats, const std::string& device,
                std::string& deviceName, std::string& driver, StepProgress& progress) {
  const render::RenderMode modes[] = {render::RenderMode::PathTrace, render::RenderMode::Hybrid,
                                      render::RenderMode::Reflections};
  json rows = json::array();
  for (const auto& bs : scenes) {
    // The reference.
    std::error_code ec;
    const std::string mtime =
        bs.path.empty() ? "generated"
                        : std::to_string(fs::last_write_time(bs.path, ec).time_since_epoch().count());
    const std::string key = "modes-reference v1 " + bs.name + " " + bs.path + " " + mtime + " " +
                            std::to_string(w) + "x" + std::to_string(h) + " spp " + std::to_string(refSpp) +
                            " shaders " + render::shaderSourceFingerprint();
    const fs::path refFile =
        shaderCacheDir() / "references" / (shader::Hasher().add(key).finish().hex() + ".exr");
    eval::ImageRGBA reference;
    double refSeconds = 0;
    progress.step(bs.name + " reference, " + std::to_string(refSpp) + " spp at " + std::to_string(w) + "x" +
                  std::to_string(h));
    if (fs::exists(refFile)) {
      reference = eval::readExr(refFile);
    } else {
      auto o = benchSession(bs, w, h, device);
      o.settings.seed = 0x5eed0000u;
      render::RenderSession s(o);
      refSeconds = s.render(refSpp);
      reference = s.image();
      fs::create_directories(refFile.parent_path());
      eval::writeExr(refFile, reference);
      writeFileAtomically(refFile.string() + ".txt", key + "\n", "reference cache");
    }
    for (auto mode : modes) {
      progress.step(bs.name + " in mode " + render::renderModeName(mode));
      render::RenderSession s(benchSession(bs, w, h, device, mode));
      deviceName = s.context().deviceName();
      driver = s.context().driverInfo();
      s.render(1);  // warm-up (the driver compiles pipelines at the first use)
      s.render(1);
      const eval::ImageRGBA one = s.image();
      s.render(frames);
      const eval::ImageRGBA many = s.image();
      json r;
      r["scene"] = bs.name;
      r["mode"] = render::renderModeName(mode);
      r["size"] = std::to_string(w) + "x" + std::to_string(h);
      r["triangles"] = s.scene().triangleCount();
      r["seconds_per_frame"] = median(s.frameSeconds());
      r["frames"] = frames;
      r["rmse_1_frame"] = eval::rmse(one, reference);
      r["rel_mse_1_frame"] = eval::relMse(one, reference, 0.01);
      r["rmse"] = eval::rmse(many, reference);
      r["rel_mse"] = eval::relMse(many, reference, 0.01);
      const auto mean = eval::meanRgb(many), refMean = eval::meanRgb(reference);
      r["mean_rgb"] = {mean[0], mean[1], mean[2]};
      r["reference_mean_rgb"] = {refMean[0], refMean[1], refMean[2]};
      r["reference"] = {{"spp", refSpp}, {"file", refFile.string()}, {"seconds", refSeconds}};
      rows.push_back(r);
    }
  }
  // Speed at the size on the default scene: time per frame of each mode for the same view.
  json speed = json::array();
  unsigned sw = 0, sh = 0;
  if (std::sscanf(speedSize.c_str(), "%ux%u", &sw, &sh) == 2 && sw && sh) {
    for (auto mode : modes) {
      progress.step(std::string("default scene, mode ") + render::renderModeName(mode) + " at " + speedSize);
      render::RenderSession s(benchSession(scenes.front(), sw, sh, device, mode));
      s.render(1);  // warm-up
      std::vector<double> t;
      for (int r = 0; r < repeats; ++r) {
        s.render(1);
        t.push_back(s.frameSeconds().front());
      }
      speed.push_back({{"mode", render::renderModeName(mode)},
                       {"size", speedSize},
                       {"seconds_per_frame", median(t)},
                       {"repeats", repeats},
                       {"pass_ms", passMsJson(s.renderer().passTimer())}});  // the last frame's passes
    }
  }
  return {{"error", rows}, {"speed", speed}};
}

// The path tracer section's scenes: the default scene, the DamagedHelmet (when ../shared has it) and a
// generated heavy scene.
std::vector<BenchScene> pathTracerScenes(bool quick) {
  std::vector<BenchScene> scenes = {{"default", defaultScenePath().string(), std::nullopt}};
  const fs::path helmet = sharedDir() / "assets/gltf/DamagedHelmet/DamagedHelmet.gltf";
  if (fs::exists(helmet)) {
    scenes.push_back({"DamagedHelmet", helmet.string(), std::nullopt});
  } else {
    std::fprintf(stderr, "bench: %s not found (set WB_SHARED_DIR); skipping it\n", helmet.string().c_str());
  }
  scenes.push_back({"heavy-1M", "", scene::makeHeavyScene(quick ? 100000 : 1000000)});
  return scenes;
}

// The modes section's scenes: the default scene and two of ../shared's models, where present.
std::vector<BenchScene> modesScenes() {
  std::vector<BenchScene> scenes = {{"default", defaultScenePath().string(), std::nullopt}};
  for (const char* rel :
       {"assets/gltf/DamagedHelmet/DamagedHelmet.gltf", "assets/gltf/vulkan-samples/teapot.gltf"}) {
    const fs::path p = sharedDir() / rel;
    if (fs::exists(p)) {
      scenes.push_back({p.stem().string(), p.string(), std::nullopt});
    } else {
      std::fprintf(stderr, "bench: %s not found (set WB_SHARED_DIR); skipping it\n", p.string().c_str());
    }
  }
  return scenes;
}

// Rates of every scene, specialised and generic; then the default scene's specialised build at the other
// roofline sizes (on a CPU device only those up to 512x512 unless the user named them).
json benchPathTracerSection(const std::vector<BenchScene>& scenes, uint32_t w, uint32_t h, uint32_t spp,
                            const std::string& size, const std::vector<std::string>& rooflineSizes,
                            bool sizesGiven, int repeats, const std::string& device, std::string& deviceName,
                            std::string& driver, StepProgress& progress) {
  json rows = json::array();
  bool cpuDevice = false;
  const auto add = [&](const BenchScene& bs, bool generic, uint32_t rw, uint32_t rh) {
    json r = benchPathTracer(bs, generic, rw, rh, spp, repeats, device, deviceName, driver, &cpuDevice);
    r["scene"] = bs.name;
    r["variant"] = generic ? "generic" : "specialised";
    r["size"] = std::to_string(rw) + "x" + std::to_string(rh);
    r["spp_per_run"] = spp;
    r["repeats"] = repeats;
    rows.push_back(r);
  };
  for (const auto& bs : scenes) {
    for (bool generic : {false, true}) {
      progress.step("path tracer on " + bs.name + (generic ? " (generic)" : " (specialised)") + " at " +
                    size);
      add(bs, generic, w, h);
    }
  }
  for (const auto& extra : rooflineSizes) {
    unsigned rw = 0, rh = 0;
    std::sscanf(extra.c_str(), "%ux%u", &rw, &rh);
    if (extra == size) continue;
    if (cpuDevice && !sizesGiven && uint64_t(rw) * rh > 512u * 512u) {
      progress.step("roofline at " + extra + ": skipped on a CPU device (--roofline-sizes runs it)");
      continue;
    }
    progress.step("path tracer and roofline on " + scenes.front().name + " at " + extra);
    add(scenes.front(), false, rw, rh);
  }
  return rows;
}

// The summary table of the sections that ran.
void printSummary(const json& result, const std::string& cmdline) {
  std::printf("%s on %s (%s), %s\n", cmdline.c_str(), result.value("device", std::string("?")).c_str(),
              result.value("driver", std::string("?")).c_str(), result["date"].get<std::string>().c_str());
  if (result.contains("pathtracer")) {
    std::printf("%-14s %-12s %10s %12s %12s %12s %12s %12s %9s\n", "scene", "variant", "triangles", "paths/s",
                "rays/s", "primary/s", "bounce/s", "shadow/s", "BLAS ms");
    for (const auto& r : result["pathtracer"]) {
      std::printf("%-14s %-12s %10zu %12.3g %12.3g %12.3g %12.3g %12.3g %9.1f\n",
                  r["scene"].get<std::string>().c_str(), r["variant"].get<std::string>().c_str(),
                  r["triangles"].get<size_t>(), r["paths_per_second"].get<double>(),
                  r["rays_per_second"].get<double>(), r["primary_rays_per_second"].get<double>(),
                  r["bounce_rays_per_second"].get<double>(), r["shadow_rays_per_second"].get<double>(),
                  r["blas_build_ms"].get<double>());
    }
  }
  if (result.contains("pathtracer")) {
    std::printf("%-14s %-10s %12s %12s %12s %12s %12s %9s %9s   (roofline: rays/s, GPU time)\n", "scene",
                "size", "bare prim.", "bare diff.", "bare shadow", "bare path", "pathtracer", "pt/diff",
                "pt/path");
    for (const auto& r : result["pathtracer"]) {
      if (!r.contains("pathtracer_vs_bare_diffuse_ratio")) continue;
      std::printf(
          "%-14s %-10s %12.3g %12.3g %12.3g %12.3g %12.3g %9.3f %9.3f\n",
          r["scene"].get<std::string>().c_str(), r["size"].get<std::string>().c_str(),
          r["bare_primary_rays_per_second"].get<double>(), r["bare_diffuse_rays_per_second"].get<double>(),
          r["bare_shadow_rays_per_second"].get<double>(), r["bare_path_rays_per_second"].get<double>(),
          r["pathtracer_gpu_rays_per_second"].get<double>(),
          r["pathtracer_vs_bare_diffuse_ratio"].get<double>(),
          r["pathtracer_vs_bare_path_ratio"].get<double>());
    }
  }
  if (result.contains("modes")) {
    std::printf("%-14s %-12s %9s %12s %12s %12s %12s %12s\n", "scene", "mode", "size", "s/frame", "RMSE 1f",
                "relMSE 1f", "RMSE Nf", "relMSE Nf");
    for (const auto& r : result["modes"]["error"]) {
      std::printf("%-14s %-12s %9s %12.4g %12.4g %12.4g %12.4g %12.4g\n",
                  r["scene"].get<std::string>().c_str(), r["mode"].get<std::string>().c_str(),
                  r["size"].get<std::string>().c_str(), r["seconds_per_frame"].get<double>(),
                  r["rmse_1_frame"].get<double>(), r["rel_mse_1_frame"].get<double>(),
                  r["rmse"].get<double>(), r["rel_mse"].get<double>());
    }
    for (const auto& r : result["modes"]["speed"]) {
      std::printf("default scene %-12s at %s: %.3f s per frame\n", r["mode"].get<std::string>().c_str(),
                  r["size"].get<std::string>().c_str(), r["seconds_per_frame"].get<double>());
    }
  }
  if (result.contains("startup")) std::printf("start-up: %s\n", jsonText(result["startup"]).c_str());
  if (result.contains("hot_reload")) std::printf("hot reload: %s\n", jsonText(result["hot_reload"]).c_str());
  if (result.contains("window")) std::printf("window: %s\n", jsonText(result["window"]).c_str());
  if (result.contains("cost")) {
    for (const auto& r : result["cost"]["variants"])
      std::printf("variant %-8s %10.4g s/sample  overhead %+6.1f%%  path tracer GPU %+6.1f%%\n",
                  r["variant"].get<std::string>().c_str(), r["seconds_per_sample"].get<double>(),
                  100.0 * r["overhead"].get<double>(), 100.0 * r["pathtracer_gpu_overhead"].get<double>());
  }
  if (result.contains("denoise")) std::printf("denoise: %s\n", jsonText(result["denoise"]).c_str());
  std::printf("peak RSS: %.0f MB\n", result["peak_rss_mb"].get<double>());
}

}  // namespace

const std::vector<std::string>& BenchCommand::sectionNames() {
  static const std::vector<std::string> names = {"pathtracer", "startup", "reload", "modes",
                                                 "window",     "denoise", "cost"};
  return names;
}

void BenchCommand::addFlags(CLI::App& cli) {
  cli.add_flag("--quick", quick, "small sizes and few repeats (a smoke run)");
  cli.add_option("--out", out, "write the results as JSON");
  cli.add_option("--device", device, "Vulkan device name (substring)");
  cli.add_option("--size", size, "trace size WxH (default 512x512, 128x128 with --quick)");
  cli.add_option("--repeats", repeats, "repeats per measurement (median reported)");
  cli.add_option(
      "--edits", edits,
      "reload: number of closest-hit edits (default 20, 4 with --quick); window: edits timed idle and "
      "under load (default 5, 2 with --quick)");
  cli.add_option(
      "--clicks", clicks,
      "window: synthetic clicks on widgets timed to the screen, idle and under load (default 12, 8 "
      "with --quick; 0: none)");
  cli.add_flag("--no-load", noLoad, "window: skip the edits with two busy loops in another session");
  cli.add_option(
         "--roofline-sizes", rooflineSizes,
         "pathtracer: more sizes WxH for the default scene with its roofline (default 256x256,2048x2048; "
         "none with --quick; above 512x512 skipped on a CPU device unless given)")
      ->delimiter(',');
  cli.add_option(
         "--only", sections,
         "sections to run, comma or space separated: pathtracer,startup,reload,modes,window,denoise,cost")
      ->delimiter(',')
      ->check(CLI::IsMember(sectionNames()));
}

void BenchCommand::finish() {
  if (size.empty()) size = quick ? "128x128" : "512x512";
  if (repeats <= 0) repeats = quick ? 1 : 3;
  if (clicks < -1 || clicks > 10000) throw std::invalid_argument("--clicks: expected 0 .. 10000");
  rooflineSizesGiven = !rooflineSizes.empty();
  if (!rooflineSizesGiven && !quick) rooflineSizes = {"256x256", "2048x2048"};
  for (const auto& rs : rooflineSizes) {
    unsigned rw = 0, rh = 0;
    if (std::sscanf(rs.c_str(), "%ux%u", &rw, &rh) != 2 || !rw || !rh)
      throw std::invalid_argument("--roofline-sizes: expected WxH, got '" + rs + "'");
  }
  unsigned w = 0, h = 0;
  if (std::sscanf(size.c_str(), "%ux%u", &w, &h) != 2 || !w || !h)
    throw std::invalid_argument("--size: expected WxH, got '" + size + "'");
  if (!out.empty()) requireWritableFile(out, "--out");  // checked before the suite runs, not after
}

int runBenchCommand(const std::vector<std::string>& args) {
  BenchCommand c;
  return runCommand(c, args);
}

int BenchCommand::run() {
  unsigned w = 0, h = 0;
  std::sscanf(size.c_str(), "%ux%u", &w, &h);
  const uint32_t spp = quick ? 1 : 4;
  const auto has = [&](const char* s) {
    return std::find(sections.begin(), sections.end(), s) != sections.end();
  };
  std::string cmdline = "workbench bench";
  for (const auto& a : args) cmdline += " " + a;

  json result;
  result["command"] = cmdline;
  // Switches that change what is measured (WB_JIT_WARMUP, WB_PIPELINE_LIBRARY, GALLIVM_PERF, ...), as set by
  // the user or, for the driver defaults, by the workbench.
  const bool ownMesaCache = envOr("MESA_SHADER_CACHE_DIR").empty();  // before the defaults fill it in
  vk::applyDriverDefaults(shaderCacheDir());
  json environment = json::object();
  for (const char* name : {"WB_JIT_WARMUP", "WB_REBUILD_YIELD", "WB_PIPELINE_LIBRARY", "WB_DEFERRED_HOST_OPS",
                           "GALLIVM_PERF", "LP_NUM_THREADS", "LP_NATIVE_VECTOR_WIDTH",
                           "MESA_SHADER_CACHE_DIR", "VK_DRIVER_FILES", "__GL_SHADER_DISK_CACHE"}) {
    if (const auto v = env::get(name)) environment[name] = *v;
  }
  result["environment"] = environment;
  result["date"] = isoDate();
  result["machine"] = machineInfo();
  const fs::path work = fs::temp_directory_path() / ("wb_bench_" + std::to_string(::getpid()));
  fs::create_directories(work);
  // The steps, counted before the first one runs (for the progress line's ETA).
  const auto ptScenes = has("pathtracer") ? pathTracerScenes(quick) : std::vector<BenchScene>{};
  const auto mScenes = has("modes") ? modesScenes() : std::vector<BenchScene>{};
  WindowBenchOptions wo;
  wo.rounds = quick ? 1 : repeats;
  wo.samples = quick ? 3 : 8;
  wo.edits = edits > 0 ? edits : quick ? 2 : 5;
  wo.underLoad = !noLoad;
  wo.clicks = clicks >= 0 ? clicks : quick ? 8 : 12;
  wo.device = device;
  DenoiseBenchOptions dno;
  dno.width = w;
  dno.height = h;
  dno.repeats = repeats;
  dno.quick = quick;
  dno.device = device;
  const int steps = int(ptScenes.size()) * 2 + (has("pathtracer") ? int(rooflineSizes.size()) : 0) +
                    (has("startup") ? 1 : 0) + (has("reload") ? 1 : 0) +
                    (has("modes") ? int(mScenes.size()) * 4 + 3 : 0) +
                    (has("window") ? windowBenchSteps(wo) : 0) +
                    (has("denoise") ? denoiseBenchSteps(dno) : 0) + (has("cost") ? 1 : 0);
  StepProgress progress("bench", steps);
  try {
    if (has("pathtracer")) {
      std::string deviceName, driver;
      result["pathtracer"] =
          benchPathTracerSection(ptScenes, w, h, spp, size, rooflineSizes, rooflineSizesGiven, repeats,
                                 device, deviceName, driver, progress);
      result["device"] = deviceName;
      result["driver"] = driver;
    }
    if (has("startup")) {
      progress.step("start-up (cold and warm)");
      result["startup"] = benchStartup(repeats, work);
    }
    if (has("reload")) {
      progress.step("hot reload");
      result["hot_reload"] = benchHotReload(edits > 0 ? edits
                                            : quick   ? 4
                                                      : 20,
                                            quick ? "64x64" : "128x128", work, ownMesaCache);
    }
    if (has("modes")) {
      std::string deviceName, driver;
      result["modes"] =
          benchModes(mScenes, quick ? 64 : 128, quick ? 64 : 128, quick ? 64 : 1024, quick ? 4 : 16,
                     quick ? "320x180" : "1280x720", repeats, device, deviceName, driver, progress);
      result["device"] = deviceName;
      result["driver"] = driver;
    }
    if (has("window")) {
      result["window"] = benchWindow(wo, work, ownMesaCache, progress);
      result["device"] = result["window"]["device"];
      result["driver"] = result["window"]["driver"];
    }
    if (has("denoise")) {
      result["denoise"] = benchDenoise(dno, progress);
      result["device"] = result["denoise"]["cost"][0]["device"];
      result["driver"] = result["denoise"]["cost"][0]["driver"];
    }
    if (has("cost")) {
      progress.step("cost, inspect and asserts variants");
      std::string deviceName, driver;
      result["cost"] = benchCostVariants(w, h, spp, quick ? 2 : repeats + 2, device, deviceName, driver);
      result["device"] = deviceName;
      result["driver"] = driver;
    }
    result["peak_rss_mb"] = peakRssMb();
  } catch (const std::exception& e) {
    progress.note("workbench bench: error: " + std::string(e.what()));
    fs::remove_all(work);
    return 1;
  }
  fs::remove_all(work);

  printSummary(result, cmdline);
  if (!out.empty()) {
    try {
      writeJsonFile(out, result, "--out");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "workbench bench: error: %s\n", e.what());
      return 1;
    }
    std::printf("wrote %s\n", out.c_str());
  }
  return 0;
}

}  // namespace wb::app
