#include "app/sweep/sweep_task.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>

#include "app/converge_run.h"
#include "app/progress.h"
#include "app/sweep/sweep_spec.h"
#include "app/sweep/sweep_state.h"
#include "common/env.h"
#include "common/json_text.h"
#include "common/paths.h"
#include "eval/metrics.h"
#include "render/render_session.h"
#include "scene/scene.h"

using nlohmann::json;

namespace wb::app::sweep {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string hostName() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "?";
  return buf;
}

std::string nowText() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S%z", std::localtime(&t));
  return buf;
}

// The image is written beside its final name and renamed: a reader never sees half an image.
void writeExrAtomically(const fs::path& path, const eval::ImageRGBA& image) {
  const fs::path tmp = path.string() + ".tmp.exr";
  eval::writeExr(tmp, image);
  fs::rename(tmp, path);
}

json shaderCacheJson(render::RenderSession& session) {
  const auto st = session.library().stats();
  return json{
      {"hits", st.hits}, {"misses", st.misses}, {"compiles", st.compiles}, {"compile_ms", st.compileMs}};
}

json renderReferenceTask(const fs::path& dir, const Sweep& s, const Task& t) {
  const SceneSpec& scene = s.scenes[t.scene];
  ProgressLine progress("sweep " + t.id);
  const ReferenceRender ref = renderReference(s.sceneOptions(t.scene), scene.referenceSpp, progress);
  writeExrAtomically(taskDir(dir, t) / "reference.exr", ref.image);
  const eval::Rgb mean = eval::meanRgb(ref.image);
  return json{{"spp", scene.referenceSpp},
              {"seed", kReferenceSeed},
              {"device", ref.device},
              {"image", "reference.exr"},
              {"mean_rgb", {mean[0], mean[1], mean[2]}},
              {"render_seconds", ref.seconds},
              {"startup", {{"session_setup_seconds", ref.setupSeconds}}}};
}

json renderRunTask(const fs::path& dir, const Sweep& s, const Task& t, Clock::time_point start) {
  RenderOptions ro = s.configOptions(t.scene, t.config);
  ro.params.render.seed = s.taskSeed(t);
  // The reference: a file, or the output of the scene's reference task.
  const fs::path refPath = referenceImage(dir, s, t.scene);
  std::error_code ec;
  if (!fs::is_regular_file(refPath, ec)) {
    throw std::runtime_error("the reference of scene '" + s.scenes[t.scene].name + "' is missing (" +
                             refPath.string() + "): its task " + s.scenes[t.scene].name +
                             ".ref is not done (`workbench sweep status DIR`)");
  }
  std::string refDescription;
  const eval::ImageRGBA reference =
      loadReferenceFile(refPath.string(), ro.params.render.width, ro.params.render.height, refDescription);

  const auto loadStart = Clock::now();
  scene::Scene scene = scene::loadGltf(ro.scene.empty() ? defaultScenePath() : fs::path(ro.scene));
  const double sceneLoad = since(loadStart);
  for (const auto& w : scene.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  render::SessionOptions so = sessionOptions(ro);
  so.sceneData = std::move(scene);
  render::RenderSession session(so);
  session.renderer().resetAccumulation();
  session.renderer().resetCounters();
  const double toSession = since(start);

  // A first sample, thrown away: on drivers that compile pipelines at their first dispatch it holds that
  // compile, which is start-up, not rendering. The run then starts again from sample 0 with the same seed.
  ProgressLine progress("sweep " + t.id);
  const double firstSample = timedRender(session, 1);
  session.renderer().resetAccumulation();
  session.renderer().resetCounters();
  double seconds = 0;
  uint32_t spp = 0;
  Checkpoint cp;  // one run: its measurements at every checkpoint, in order
  json checkpoints = json::array();
  for (const uint32_t target : s.checkpoints) {
    seconds += timedRender(session, target - spp);
    spp = target;
    addMeasurement(cp, session.image(), reference, seconds);
    const fs::path image = checkpointImage(dir, t, target);
    writeExrAtomically(image, cp.images.back());
    const eval::Rgb& m = cp.mean.back();
    checkpoints.push_back(json{{"spp", target},
                               {"seconds", seconds},
                               {"mse", cp.mse.back()},
                               {"rel_mse", cp.relMse.back()},
                               {"mean_rgb", {m[0], m[1], m[2]}},
                               {"image", image.filename().string()}});
    if (cp.images.size() > 1) cp.images.erase(cp.images.begin());  // only the last one is needed
    progress.update("", double(target) / double(s.checkpoints.back()),
                    std::to_string(target) + "/" + std::to_string(s.checkpoints.back()) + " spp",
                    target == s.checkpoints.back());
  }
  progress.finish();
  const eval::FireflyStats ff = eval::fireflyStats(cp.images.back());
  const auto counters = session.renderer().readCounters();
  return json{{"seed", ro.params.render.seed},
              {"device", session.context().deviceName()},
              {"driver", session.context().driverInfo()},
              {"reference", refDescription},
              {"checkpoints", checkpoints},
              {"nan_inf_dropped", counters.droppedSamples},
              {"fireflies",
               {{"max_over_mean", ff.maxOverMean},
                {"fraction_above_10x", ff.fractionAbove10x},
                {"mean_luminance", ff.meanLuminance},
                {"max_luminance", ff.maxLuminance}}},
              {"render_seconds", seconds},
              {"startup",
               {{"scene_load_seconds", sceneLoad},
                {"session_setup_seconds", session.setupSeconds()},
                {"to_session_seconds", toSession},
                {"first_sample_seconds", firstSample},
                {"shader_cache", shaderCacheJson(session)}}}};
}

}  // namespace

int runTask(const fs::path& dir, const std::string& name, bool force) {
  const auto start = Clock::now();
  std::string id = name;
  try {
    const Sweep s = loadSweep(dir);
    const Task& t = s.tasks[s.findTask(name)];
    id = t.id;
    fs::create_directories(taskDir(dir, t));
    const FileLock lock(taskDir(dir, t) / "lock");
    if (!lock.held()) {
      std::fprintf(stderr, "workbench sweep run-task: error: task %s is running in another process\n",
                   id.c_str());
      return 1;
    }
    if (isDone(dir, t) && !force) {
      std::printf("sweep: task %s is done already (%s); --force runs it again\n", id.c_str(),
                  resultFile(dir, t).c_str());
      return 0;
    }
    std::error_code ec;
    fs::remove(resultFile(dir, t), ec);
    json attempt{{"task", t.id}, {"host", hostName()}, {"pid", ::getpid()}, {"started", nowText()}};
    const auto jobId = env::get("SLURM_JOB_ID");
    const auto arrayJob = env::get("SLURM_ARRAY_JOB_ID");
    const auto arrayTask = env::get("SLURM_ARRAY_TASK_ID");
    if (arrayJob && arrayTask) {
      attempt["slurm_job"] = *arrayJob + "_" + *arrayTask;
      attempt["slurm_log"] =
          (fs::absolute(dir) / "slurm" / "logs" / (*arrayJob + "_" + *arrayTask + ".out")).string();
    } else if (jobId) {
      attempt["slurm_job"] = *jobId;
    }
    writeFileAtomically(attemptFile(dir, t), jsonText(attempt, 2) + "\n");
    std::printf("sweep: task %s (%s) on %s, started %s\n", t.id.c_str(),
                t.kind == TaskKind::Reference ? "reference" : "run",
                attempt["host"].get<std::string>().c_str(), attempt["started"].get<std::string>().c_str());
    std::fflush(stdout);

    json result =
        t.kind == TaskKind::Reference ? renderReferenceTask(dir, s, t) : renderRunTask(dir, s, t, start);
    result["task"] = t.id;
    result["number"] = s.findTask(t.id);
    result["kind"] = t.kind == TaskKind::Reference ? "reference" : "run";
    result["scene"] = s.scenes[t.scene].name;
    if (t.kind == TaskKind::Run) {
      result["config"] = s.configs[t.config].name;
      result["seed_index"] = t.seedIndex;
    }
    result["host"] = attempt["host"];
    result["slurm_job"] = attempt.value("slurm_job", "");
    result["started"] = attempt["started"];
    result["wall_seconds"] = since(start);
    writeFileAtomically(resultFile(dir, t), jsonText(result, 1) + "\n");
    std::printf("sweep: task %s done in %.2f s\n", t.id.c_str(), since(start));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench sweep run-task %s: error: %s\n", id.c_str(), e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app::sweep
