#include "app/reload_log.h"

#include <cmath>

namespace wb::app {

nlohmann::json abJson(const live::ReloadAB& ab) {
  // Non-finite numbers (a NaN that appeared) are null in JSON.
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json j;
  j["image_verdict"] = eval::imageVerdictName(ab.image.verdict);
  j["rmse"] = num(ab.image.rmse);
  j["rel_mse"] = num(ab.image.relMse);
  j["max_abs_diff"] = num(ab.image.maxAbsDiff);
  j["changed_pixel_fraction"] = ab.image.changedPixelFraction;
  j["mean_shift_significant"] = ab.image.meanShiftSignificant;
  j["speed_ratio"] = num(ab.speed.ratio);
  j["speed_ratio_spread"] = {num(ab.speed.spread[0]), num(ab.speed.spread[1])};
  j["speed_verdict"] = eval::speedVerdictName(ab.speed.verdict);
  return j;
}

nlohmann::json reloadEventJson(const live::ReloadEvent& e) {
  nlohmann::json j;
  j["time"] = std::chrono::duration<double>(e.when.time_since_epoch()).count();
  j["files_changed"] = e.filesChanged;
  j["stages_recompiled"] = e.stagesRecompiled;
  j["pipelines_rebuilt"] = e.pipelinesRebuilt;
  j["compile_ms"] = e.compileMs;
  j["pipeline_ms"] = e.pipelineMs;
  // Linked ray tracing pipelines (GPUs): per-group libraries compiled and reused, slowest compile, link.
  j["pipeline_libraries_compiled"] = e.libraries.librariesCompiled;
  j["pipeline_libraries_reused"] = e.libraries.librariesReused;
  j["pipeline_library_ms"] = e.libraries.libraryMs;
  j["pipeline_link_ms"] = e.libraries.linkMs;
  j["edit_to_new_pipeline_ms"] = e.editToNewPipelineMs;
  if (e.editToFirstFrameMs >= 0) {
    j["edit_to_first_frame_ms"] = e.editToFirstFrameMs;
  } else {
    j["edit_to_first_frame_ms"] = nullptr;
  }
  // The frames around the reload (render/reload_frames.h); null where there was no such frame.
  auto frameMs = [](double ms) { return ms >= 0 ? nlohmann::json(ms) : nlohmann::json(nullptr); };
  j["frame_ms_median_before"] = frameMs(e.frames.medianBefore);
  j["frame_ms_max_during_rebuild"] = frameMs(e.frames.maxDuringRebuild);
  j["frame_ms_max_before_same_span"] = frameMs(e.frames.maxBeforeSameSpan);
  j["first_new_frame_ms"] = frameMs(e.frames.firstNewFrame);
  j["frames_during_rebuild"] = e.frames.framesDuringRebuild;
  j["ok"] = e.ok;
  j["error"] = e.error;
  // The A/B comparison (watch --ab, the window's A/B panel): "ab" is the active renderer's (the first),
  // "ab_pipelines" every rebuilt pipeline's with its timings, "ab_ms" what the comparisons took.
  if (!e.ab.empty()) {
    j["ab"] = abJson(e.ab.front());
    nlohmann::json list = nlohmann::json::array();
    for (const auto& ab : e.ab) {
      list.push_back(
          {{"pipeline", ab.pipeline},
           {"mode", ab.mode},
           {"active", ab.active},
           {"ab", abJson(ab)},
           {"max_rel_diff", std::isfinite(ab.image.maxRelDiff) ? nlohmann::json(ab.image.maxRelDiff)
                                                               : nlohmann::json(nullptr)},
           {"old_ms_per_sample", ab.speed.oldMsPerSample},
           {"new_ms_per_sample", ab.speed.newMsPerSample}});
    }
    j["ab_pipelines"] = list;
    j["ab_ms"] = e.abMs;
  }
  if (e.reverted) j["reverted"] = true;
  return j;
}

}  // namespace wb::app
