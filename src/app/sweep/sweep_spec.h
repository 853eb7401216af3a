// A sweep: scenes x configurations x seeds, each run to the same spp checkpoints against a reference per
// scene, expanded into tasks with stable ids (docs/sweeps.md describes the file). The sweep file (JSON) is
// read once, when the sweep is made; its folder keeps the expanded form (sweep.json), from which every task,
// status, resume and merge reads it again.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/render_options.h"

namespace wb::app::sweep {

struct SceneSpec {
  std::string name;                // letters, digits, - and _: part of task ids and file names
  std::string path;                // absolute; empty: the default scene
  std::vector<std::string> flags;  // render flags of this scene (over the sweep's)
  std::string referenceFile;       // absolute; empty: rendered by a reference task
  uint32_t referenceSpp = 0;       // the reference task's spp (when there is no file)
};

struct ConfigSpec {
  std::string name;
  std::vector<std::string> flags;  // render flags (over the scene's), --define and --mode included
};

enum class TaskKind { Reference, Run };

struct Task {
  std::string id;  // "SCENE.ref" or "SCENE.CONFIG.sK"
  TaskKind kind = TaskKind::Run;
  size_t scene = 0;
  size_t config = 0;       // runs only
  uint32_t seedIndex = 0;  // runs only: independent run K of its scene and configuration
};

struct Sweep {
  std::string name;
  std::string specFile;  // the sweep file it was made from (absolute)
  std::string size;      // WxH
  std::vector<std::string> flags;
  std::vector<SceneSpec> scenes;
  std::vector<ConfigSpec> configs;
  uint32_t seeds = 1;
  std::vector<uint32_t> checkpoints;  // spp, increasing
  double targetRelMse = 0;            // 0: the median of the final relMSEs
  std::vector<Task> tasks;            // the reference renders first, then scene x configuration x seed

  // The render options of a scene's reference (the sweep's and the scene's flags) and of one configuration
  // on a scene (the configuration's flags over those).
  RenderOptions sceneOptions(size_t scene) const;
  RenderOptions configOptions(size_t scene, size_t config) const;
  // The seed of a run task (the configuration's --seed and the task's seed index), the same wherever it runs.
  uint32_t taskSeed(const Task& task) const;
  // The task named by its id or its number (its index in `tasks`); throws std::invalid_argument.
  size_t findTask(const std::string& idOrNumber) const;
  // The reference task of a scene, or -1 when the scene's reference is a file.
  long referenceTask(size_t scene) const;
  size_t referenceCount() const;
};

// Reads a sweep file. Relative paths in it are relative to its folder. Throws std::invalid_argument naming
// the file and the line (JSON syntax) or the entry (`scenes[1].flags`) and what is wrong with it; every
// configuration's flags are parsed here, so a bad flag is found before anything runs.
Sweep readSpec(const std::filesystem::path& file);
// The same from JSON text (`source` names it in messages; `base` is the folder relative paths start from).
Sweep parseSpec(const std::string& text, const std::string& source, const std::filesystem::path& base);

// The expanded sweep as JSON (absolute paths, defaults filled in, the task ids): sweep.json. Reading it back
// gives the same sweep.
nlohmann::json toJson(const Sweep& sweep);

// The sweep of a sweep folder (DIR/sweep.json); throws std::runtime_error when DIR holds none.
Sweep loadSweep(const std::filesystem::path& dir);

// Writes `text` to `path` through a temporary file and a rename: readers see the old file or the new one.
void writeFileAtomically(const std::filesystem::path& path, const std::string& text);

}  // namespace wb::app::sweep
