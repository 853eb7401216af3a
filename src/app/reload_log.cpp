#include "app/reload_log.h"

namespace wb::app {

nlohmann::json reloadEventJson(const render::ReloadEvent& e) {
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
  return j;
}

}  // namespace wb::app
