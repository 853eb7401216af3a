// A sweep folder and what it says about each task. Everything a sweep knows lives in its folder (and, for
// `--slurm`, in Slurm's queue), so any shell on any machine that sees the folder can ask for its status,
// resume it or merge it:
//
//   DIR/sweep.json                  the expanded sweep (sweep_spec.h); never changes
//   DIR/executor.json               how its tasks were last started (local, or Slurm and its options)
//   DIR/tasks/ID/attempt.json       a task began: host, pid, Slurm job
//   DIR/tasks/ID/lock               held (flock) while the task runs
//   DIR/tasks/ID/log.txt            the task's output
//   DIR/tasks/ID/result.json        written last, atomically: the task is done
//   DIR/tasks/ID/spp_NNNNNN.exr     a run's image at each checkpoint; a reference task's reference.exr
//   DIR/local.lock                  held while `sweep --local` or `sweep resume` runs tasks here
//   DIR/slurm/                      job scripts, task lists, jobs.json (every job submitted), logs/
//   DIR/report/                     the merge: summary.md, summary.json, tasks.csv, one folder per scene
#pragma once
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/sweep/sweep_spec.h"

namespace wb::app::sweep {

namespace fs = std::filesystem;

fs::path taskDir(const fs::path& dir, const Task& t);
fs::path resultFile(const fs::path& dir, const Task& t);
fs::path attemptFile(const fs::path& dir, const Task& t);
fs::path logFile(const fs::path& dir, const Task& t);
fs::path checkpointImage(const fs::path& dir, const Task& t, uint32_t spp);
// The reference image of a scene: its file, or its reference task's output.
fs::path referenceImage(const fs::path& dir, const Sweep& s, size_t scene);

// A task's result, when it is done (its result.json parses).
std::optional<nlohmann::json> readResult(const fs::path& dir, const Task& t);
bool isDone(const fs::path& dir, const Task& t);

// An exclusive flock on a file (created when missing), held until destroyed.
class FileLock {
 public:
  // Takes the lock without waiting; held() says whether it did.
  explicit FileLock(const fs::path& path);
  ~FileLock();
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  int fd_ = -1;
};
// Whether another process holds the lock on `path` now (false when the file is missing).
bool lockedElsewhere(const fs::path& path);

// How the tasks were last started; kept in DIR/executor.json for `resume`.
struct Executor {
  std::string kind;   // "local" or "slurm"
  unsigned jobs = 0;  // local: processes at once (0: the machine's cores)
  std::string partition, gres, time;
  unsigned throttle = 0;  // Slurm array throttle (%K); 0: none
  std::vector<std::string> sbatchArgs;
};
nlohmann::json toJson(const Executor& e);
Executor executorFromJson(const nlohmann::json& j);
std::optional<Executor> readExecutor(const fs::path& dir);
void writeExecutor(const fs::path& dir, const Executor& e);

enum class State { Pending, Running, Done, Failed };
const char* stateName(State s);

// One task's state: done (result.json), running (its lock is held, or Slurm runs it), pending (queued, or
// waiting in a local run here), else failed, with the reason and its log's last lines.
struct TaskState {
  State state = State::Pending;
  std::string detail;                // "job 12_3 in Slurm: PENDING (Dependency)", "exit status 1", ...
  std::string job;                   // its Slurm job element, when it has one
  std::vector<std::string> logTail;  // failed tasks: the last lines of its log (and of Slurm's job log)
};

// What Slurm's queue says about one job or array element of this sweep.
struct QueuedJob {
  std::string job;     // "12_3" (array element) or "12"
  std::string state;   // PENDING, RUNNING, ...
  std::string reason;  // Dependency, DependencyNeverSatisfied, None, ...
  bool active() const { return reason != "DependencyNeverSatisfied"; }
};
struct QueueView {
  bool queried = false;               // squeue ran (the sweep has Slurm jobs)
  std::string error;                  // why squeue could not tell
  std::map<size_t, QueuedJob> tasks;  // task number -> its queued job element
  std::vector<QueuedJob> merges;      // this sweep's merge jobs still queued
};

std::vector<TaskState> taskStates(const fs::path& dir, const Sweep& s, const QueueView& queue,
                                  size_t tailLines = 5);

// The last `n` lines of a text file (empty when missing).
std::vector<std::string> lastLines(const fs::path& path, size_t n);

}  // namespace wb::app::sweep
