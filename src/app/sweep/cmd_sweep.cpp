#include "app/sweep/cmd_sweep.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <set>
#include <thread>

#include "app/process.h"
#include "app/progress.h"
#include "app/sweep/sweep_merge.h"
#include "app/sweep/sweep_slurm.h"
#include "app/sweep/sweep_spec.h"
#include "app/sweep/sweep_state.h"
#include "app/sweep/sweep_task.h"
#include "common/file_io.h"
#include "common/json_text.h"

using nlohmann::json;

namespace wb::app {

using namespace sweep;

namespace {

void addExecutorFlags(CLI::App& app, SweepCommand::ExecutorFlags& f) {
  app.add_flag("--local", f.local, "run the tasks as processes on this machine");
  f.jobsOption = app.add_option("-j,--jobs", f.jobs, "--local: tasks at once (default 1)");
  app.add_flag("--slurm", f.slurm, "submit the tasks as Slurm job arrays (sbatch)");
  f.slurmOptions = {
      app.add_flag("--wait", f.wait, "--slurm: wait for the merge job, then say how it went"),
      app.add_option("--partition", f.partition, "--slurm: the partition (sbatch --partition)"),
      app.add_option("--gres", f.gres, "--slurm: generic resources of each task, e.g. gpu:1 (sbatch --gres)"),
      app.add_option("--time", f.time, "--slurm: time limit of each task, e.g. 00:30:00 (sbatch --time)"),
      app.add_option("--throttle", f.throttle,
                     "--slurm: at most K tasks of an array at once (--array=...%K)"),
      app.add_option(
             "--sbatch-arg", f.sbatchArgs,
             "--slurm: one more sbatch option for every job, e.g. --sbatch-arg=--account=lab (repeatable)")
          ->allow_extra_args(false)};
}

// Exactly one executor when `required` (`resume` may keep the sweep's: then --wait alone is allowed); -j
// only with --local, the Slurm flags only with --slurm.
void checkExecutorFlags(const SweepCommand::ExecutorFlags& f, bool required) {
  if (f.local && f.slurm) throw std::invalid_argument("give --local or --slurm, not both");
  if (required && !f.local && !f.slurm)
    throw std::invalid_argument("say where the tasks run: --local or --slurm");
  if (f.jobsOption->count() && !f.local) throw std::invalid_argument("-j/--jobs goes with --local");
  if (f.jobsOption->count() && f.jobs == 0) throw std::invalid_argument("-j/--jobs: at least 1");
  for (const CLI::Option* o : f.slurmOptions) {
    const bool waitAlone = !required && !f.local && o->get_name() == "--wait";
    if (o->count() && !f.slurm && !waitAlone)
      throw std::invalid_argument(o->get_name() + " goes with --slurm");
  }
  for (const auto& a : f.sbatchArgs) {
    if (a.rfind("-", 0) != 0 || a.find('\n') != std::string::npos)
      throw std::invalid_argument("--sbatch-arg: expected one sbatch option such as --account=lab, got '" +
                                  a + "'");
    for (const char* ours : {"--array", "--dependency", "--output", "--chdir", "--job-name", "--parsable"})
      if (a.rfind(ours, 0) == 0)
        throw std::invalid_argument("--sbatch-arg: " + std::string(ours) + " is set by the sweep itself");
  }
}

// Runs tasks as child processes here, at most `jobs` at once; a run waits for its scene's reference. Holds
// DIR/local.lock meanwhile. Returns the tasks that did not end done.
std::vector<size_t> runLocally(const fs::path& dir, const Sweep& s, std::vector<size_t> todo, unsigned jobs) {
  const FileLock lock(dir / "local.lock");
  if (!lock.held())
    throw std::runtime_error("another local run of this sweep is running (DIR/local.lock is held)");
  InterruptRequest interrupt;
  const std::string self = selfExecutable();
  struct Running {
    ChildProcess child;
    size_t task;
    std::chrono::steady_clock::time_point start;
  };
  std::vector<Running> running;
  std::vector<size_t> failed;
  std::set<size_t> failedScenes;  // scenes whose reference failed: their runs cannot start
  const size_t total = todo.size();
  size_t finished = 0;
  while (!todo.empty() || !running.empty()) {
    if (interrupt.requested()) {
      for (auto& r : running) r.child.terminate();
      for (auto& r : running) failed.push_back(r.task);
      failed.insert(failed.end(), todo.begin(), todo.end());
      std::fprintf(stderr, "sweep: interrupted; `workbench sweep resume %s` runs what is not done\n",
                   dir.c_str());
      return failed;
    }
    for (auto it = todo.begin(); it != todo.end() && running.size() < jobs;) {
      const Task& t = s.tasks[*it];
      const long ref = s.referenceTask(t.scene);
      const bool refPending = t.kind == TaskKind::Run && ref >= 0 && !isDone(dir, s.tasks[size_t(ref)]);
      if (t.kind == TaskKind::Run && failedScenes.count(t.scene)) {
        std::printf("sweep: [%zu/%zu] %s not run: the reference of its scene failed\n", ++finished, total,
                    t.id.c_str());
        failed.push_back(*it);
        it = todo.erase(it);
        continue;
      }
      if (refPending) {
        ++it;
        continue;
      }
      fs::create_directories(taskDir(dir, t));
      running.push_back(
          {ChildProcess::spawn(self, {"sweep", "run-task", dir.string(), t.id}, {}, logFile(dir, t).string()),
           *it, std::chrono::steady_clock::now()});
      it = todo.erase(it);
    }
    bool any = false;
    for (auto it = running.begin(); it != running.end();) {
      if (!it->child.exited()) {
        ++it;
        continue;
      }
      any = true;
      const Task& t = s.tasks[it->task];
      const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - it->start).count();
      if (it->child.exitStatus == 0 && isDone(dir, t)) {
        std::printf("sweep: [%zu/%zu] %s done (%.1f s)\n", ++finished, total, t.id.c_str(), secs);
      } else {
        std::printf("sweep: [%zu/%zu] %s FAILED (exit %d, %.1f s); its log %s ends:\n", ++finished, total,
                    t.id.c_str(), it->child.exitStatus, secs, logFile(dir, t).c_str());
        for (const auto& line : lastLines(logFile(dir, t), 5)) std::printf("    | %s\n", line.c_str());
        failed.push_back(it->task);
        if (t.kind == TaskKind::Reference) failedScenes.insert(t.scene);
      }
      std::fflush(stdout);
      it = running.erase(it);
    }
    // A run whose reference is pending with nothing running would wait forever: it cannot happen, since
    // references come first in `todo`; sleep only while children run.
    if (!any && !running.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    if (running.empty() && !todo.empty()) {
      bool startable = false;
      for (size_t i : todo) {
        const Task& t = s.tasks[i];
        const long ref = s.referenceTask(t.scene);
        startable |= t.kind == TaskKind::Reference || ref < 0 || isDone(dir, s.tasks[size_t(ref)]) ||
                     failedScenes.count(t.scene);
      }
      if (!startable) {
        for (size_t i : todo) {
          std::printf("sweep: %s not run: its scene's reference is not done and not among the tasks to run\n",
                      s.tasks[i].id.c_str());
          failed.push_back(i);
        }
        todo.clear();
      }
    }
  }
  return failed;
}

int mergeHere(const fs::path& dir, const Sweep& s) {
  const MergeResult r = mergeSweep(dir, s, false);
  if (!r.written) {
    std::fprintf(stderr, "workbench sweep: error: %s\n", r.message.c_str());
    return 1;
  }
  std::printf("sweep: merged %zu task(s) -> %s\n", s.tasks.size(), (dir / "report" / "summary.md").c_str());
  return 0;
}

int finishLocal(const fs::path& dir, const Sweep& s, const std::vector<size_t>& todo, unsigned jobs) {
  const std::vector<size_t> failed = runLocally(dir, s, todo, std::max(1u, jobs));
  if (!failed.empty()) {
    std::string ids;
    for (size_t i = 0; i < failed.size() && i < 20; ++i) ids += (i ? ", " : "") + s.tasks[failed[i]].id;
    std::fprintf(stderr,
                 "workbench sweep: %zu task(s) not done: %s%s; no report (`workbench sweep status %s`, then "
                 "`workbench sweep resume %s`)\n",
                 failed.size(), ids.c_str(), failed.size() > 20 ? ", ..." : "", dir.c_str(), dir.c_str());
    return 1;
  }
  return mergeHere(dir, s);
}

// Waits until the merge job has left the queue, or can never start. Returns the exit status.
int waitForMerge(const fs::path& dir, const Sweep& s, const std::string& mergeJob) {
  ProgressLine progress("sweep");
  while (true) {
    const QueueView q = queryQueue(dir, s);
    if (!q.error.empty()) {
      std::fprintf(stderr, "workbench sweep: error: --wait: %s", q.error.c_str());
      return 1;
    }
    const auto states = taskStates(dir, s, q, 0);
    size_t done = 0, run = 0, failed = 0;
    for (const auto& st : states) {
      done += st.state == State::Done;
      run += st.state == State::Running;
      failed += st.state == State::Failed;
    }
    const QueuedJob* merge = nullptr;
    for (const auto& m : q.merges)
      if (m.job == mergeJob) merge = &m;
    char detail[128];
    std::snprintf(detail, sizeof detail, "%zu/%zu done, %zu running, %zu failed; merge job %s %s", done,
                  states.size(), run, failed, mergeJob.c_str(), merge ? merge->state.c_str() : "ended");
    progress.update("tasks", double(done) / double(std::max<size_t>(1, states.size())), detail);
    if (merge && !merge->active()) {
      progress.finish();
      std::fprintf(stderr,
                   "workbench sweep: the merge job %s can never start: %zu task(s) failed (`workbench sweep "
                   "status %s`, then `workbench sweep resume %s`)\n",
                   mergeJob.c_str(), failed, dir.c_str(), dir.c_str());
      return 1;
    }
    if (!merge) {
      progress.update("tasks", double(done) / double(std::max<size_t>(1, states.size())), detail, true);
      progress.finish();
      const auto text = readRegularFile(dir / "report" / "summary.json");
      json summary;
      try {
        if (text) summary = json::parse(*text);
      } catch (const json::exception&) {
      }
      if (summary.is_object() && summary.value("merge_job", "") == mergeJob) {
        std::printf("sweep: merged by job %s -> %s\n", mergeJob.c_str(),
                    (dir / "report" / "summary.md").c_str());
        return 0;
      }
      std::fprintf(stderr, "workbench sweep: the merge job %s ended without a report; its log (%s) ends:\n",
                   mergeJob.c_str(), (dir / "slurm" / "logs" / ("merge_" + mergeJob + ".out")).c_str());
      for (const auto& line : lastLines(dir / "slurm" / "logs" / ("merge_" + mergeJob + ".out"), 10))
        std::fprintf(stderr, "    | %s\n", line.c_str());
      return 1;
    }
    std::this_thread::sleep_for(std::chrono::seconds(2));
  }
}

int submit(const fs::path& dir, const Sweep& s, const std::vector<size_t>& todo, const Executor& e, bool wait,
           const std::vector<std::string>& referenceJobs = {},
           const std::vector<std::string>& activeJobs = {}) {
  const Submission sub = submitToSlurm(dir, s, todo, e, referenceJobs, activeJobs);
  auto list = [](const std::vector<std::string>& ids) {
    std::string out;
    for (const auto& id : ids) out += (out.empty() ? "" : ",") + id;
    return out;
  };
  size_t refs = 0;
  for (size_t t : todo) refs += s.tasks[t].kind == TaskKind::Reference;
  std::printf("sweep: submitted %zu task(s) to Slurm: %zu reference render(s)%s, %zu run(s)%s, merge job %s",
              todo.size(), refs,
              sub.referenceJobs.empty() ? "" : (" (job " + list(sub.referenceJobs) + ")").c_str(),
              todo.size() - refs, sub.runJobs.empty() ? "" : (" (job " + list(sub.runJobs) + ")").c_str(),
              sub.mergeJob.c_str());
  std::printf("\nsweep: job scripts in %s; `workbench sweep status %s` follows it\n", (dir / "slurm").c_str(),
              dir.c_str());
  std::fflush(stdout);
  return wait ? waitForMerge(dir, s, sub.mergeJob) : 0;
}

}  // namespace

void SweepCommand::addFlags(CLI::App& app) {
  app.add_option("spec", spec_, "the sweep file (JSON; docs/sweeps.md)");
  app.add_option("--out", out_, "the sweep's folder: its tasks' outputs, state and report");
  addExecutorFlags(app, create_);

  status_ = app.add_subcommand("status", "Each task's state: pending, running, done, failed (with its log)");
  status_->add_option("dir", dir_, "the sweep's folder")->required();
  status_->add_flag("--json", json_, "as JSON");
  status_->add_flag("--all", all_, "list the tasks that are done too");

  resume_ =
      app.add_subcommand("resume", "Run again what is not done (and not queued or running), then merge");
  resume_->add_option("dir", dir_, "the sweep's folder")->required();
  addExecutorFlags(*resume_, again_);

  merge_ = app.add_subcommand("merge", "Build the report from the tasks' results");
  merge_->add_option("dir", dir_, "the sweep's folder")->required();
  merge_->add_flag("--partial", partial_, "report without the tasks that are not done (and name them)");

  runTask_ = app.add_subcommand("run-task", "Run one task (what the executors start)");
  runTask_->add_option("dir", dir_, "the sweep's folder")->required();
  runTask_->add_option("task", task_, "the task's id or number")->required();
  runTask_->add_flag("--force", force_, "run it even when it is done");
}

void SweepCommand::finish() {
  if (status_->parsed() || resume_->parsed() || merge_->parsed() || runTask_->parsed()) {
    if (!spec_.empty() || !out_.empty() || create_.local || create_.slurm)
      throw std::invalid_argument(
          "give SPEC, --out and the executor to `sweep SPEC ...` alone, not with a subcommand");
    if (resume_->parsed()) checkExecutorFlags(again_, false);
    return;
  }
  if (spec_.empty())
    throw std::invalid_argument("expected a sweep file: workbench sweep SPEC (--local | --slurm) --out DIR");
  if (out_.empty()) throw std::invalid_argument("--out DIR is required");
  checkExecutorFlags(create_, true);
}

sweep::Executor SweepCommand::executor(const ExecutorFlags& f, const Executor& fallback) const {
  if (!f.local && !f.slurm) return fallback;
  Executor e;
  e.kind = f.local ? "local" : "slurm";
  e.jobs = f.jobs ? f.jobs : 1;
  e.partition = f.partition;
  e.gres = f.gres;
  e.time = f.time;
  e.throttle = f.throttle;
  e.sbatchArgs = f.sbatchArgs;
  return e;
}

int SweepCommand::run() {
  try {
    if (status_->parsed()) return status();
    if (resume_->parsed()) return resume();
    if (merge_->parsed()) return runMerge(dir_, partial_);
    if (runTask_->parsed()) return runTask(dir_, task_, force_);
    return create();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench sweep: error: %s\n", e.what());
    return 1;
  }
}

int SweepCommand::create() {
  Sweep s;
  try {
    s = readSpec(spec_);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "workbench sweep: error: %s\n", e.what());
    return kUsageError;
  }
  const fs::path dir(out_);
  std::error_code ec;
  if (fs::exists(dir / "sweep.json", ec)) {
    std::fprintf(
        stderr,
        "workbench sweep: error: --out: '%s' holds a sweep already: `workbench sweep resume %s` goes on "
        "with it; give another folder for a new one\n",
        dir.c_str(), dir.c_str());
    return kUsageError;
  }
  try {
    requireWritableDirectory(dir, "--out");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench sweep: error: %s\n", e.what());
    return kUsageError;
  }
  json ids = json::array();
  for (const auto& t : s.tasks) ids.push_back(t.id);
  if (const auto text = readRegularFile(spec_)) writeFileAtomically(dir / "spec.json", *text);
  writeFileAtomically(
      dir / "sweep.json",
      jsonText(json{{"format", 1}, {"spec_file", s.specFile}, {"sweep", toJson(s)}, {"tasks", ids}}, 1) +
          "\n");
  const Executor e = executor(create_, {});
  writeExecutor(dir, e);
  std::printf(
      "sweep %s: %zu task(s) (%zu reference render(s); %zu scene(s) x %zu configuration(s) x %u seed(s)) "
      "in %s\n",
      s.name.c_str(), s.tasks.size(), s.referenceCount(), s.scenes.size(), s.configs.size(), s.seeds,
      dir.c_str());
  std::fflush(stdout);
  std::vector<size_t> all(s.tasks.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  if (e.kind == "local") return finishLocal(dir, s, all, e.jobs);
  return submit(dir, s, all, e, create_.wait);
}

int SweepCommand::status() {
  const fs::path dir(dir_);
  const Sweep s = loadSweep(dir);
  const QueueView q = queryQueue(dir, s);
  const auto states = taskStates(dir, s, q, 5);
  size_t count[4] = {0, 0, 0, 0};
  for (const auto& st : states) ++count[size_t(st.state)];
  const auto e = readExecutor(dir);
  if (json_) {
    json j{
        {"sweep", s.name},
        {"dir", dir.string()},
        {"executor", e ? toJson(*e) : json()},
        {"counts", {{"pending", count[0]}, {"running", count[1]}, {"done", count[2]}, {"failed", count[3]}}},
        {"tasks", json::array()},
        {"merge_jobs", json::array()}};
    if (!q.error.empty()) j["queue_error"] = q.error;
    for (size_t i = 0; i < states.size(); ++i) {
      j["tasks"].push_back(json{{"number", i},
                                {"id", s.tasks[i].id},
                                {"state", stateName(states[i].state)},
                                {"detail", states[i].detail},
                                {"job", states[i].job},
                                {"log_tail", states[i].logTail}});
    }
    for (const auto& m : q.merges)
      j["merge_jobs"].push_back(json{{"job", m.job}, {"state", m.state}, {"reason", m.reason}});
    std::error_code ec;
    j["report"] = fs::exists(dir / "report" / "summary.json", ec);
    std::printf("%s\n", jsonText(j, 1).c_str());
    return 0;
  }
  std::printf("sweep %s (%s), %s: %zu task(s): %zu done, %zu running, %zu pending, %zu failed\n",
              s.name.c_str(), dir.c_str(), e ? e->kind.c_str() : "?", states.size(), count[2], count[1],
              count[0], count[3]);
  if (!q.error.empty()) std::printf("  (Slurm's queue could not be read: %s)\n", q.error.c_str());
  for (const auto& m : q.merges)
    std::printf("  merge job %s: %s (%s)\n", m.job.c_str(), m.state.c_str(), m.reason.c_str());
  for (size_t i = 0; i < states.size(); ++i) {
    const TaskState& st = states[i];
    if (st.state == State::Done && !all_) continue;
    std::printf("  %-8s %s%s%s\n", stateName(st.state), s.tasks[i].id.c_str(), st.detail.empty() ? "" : ": ",
                st.detail.c_str());
    if (st.state == State::Failed) {
      if (st.logTail.empty()) std::printf("      (no log)\n");
      for (const auto& line : st.logTail) std::printf("      | %s\n", line.c_str());
    }
  }
  std::error_code ec;
  if (count[2] == states.size()) {
    std::printf("  every task is done; report: %s\n", fs::exists(dir / "report" / "summary.md", ec)
                                                          ? (dir / "report" / "summary.md").c_str()
                                                          : "not merged yet (`workbench sweep merge DIR`)");
  } else if (count[3] > 0) {
    std::printf("  `workbench sweep resume %s` runs the failed tasks again\n", dir.c_str());
  }
  return 0;
}

int SweepCommand::resume() {
  const fs::path dir(dir_);
  const Sweep s = loadSweep(dir);
  if (lockedElsewhere(dir / "local.lock"))
    throw std::runtime_error("a local run of this sweep is running here: let it end (or stop it) first");
  const auto recorded = readExecutor(dir);
  if (!recorded && !again_.local && !again_.slurm)
    throw std::runtime_error("DIR/executor.json is missing: say where the tasks run, --local or --slurm");
  const Executor e = executor(again_, recorded.value_or(Executor{}));
  const QueueView q = queryQueue(dir, s);
  if (!q.error.empty())
    throw std::runtime_error("cannot tell what Slurm still runs of this sweep: " + q.error);
  const auto states = taskStates(dir, s, q, 0);
  std::vector<size_t> todo;
  std::vector<std::string> stuck, activeJobs;
  std::set<std::string> activeArrays, activeReferences;
  for (size_t i = 0; i < states.size(); ++i) {
    if (states[i].state == State::Failed) {
      todo.push_back(i);
      const auto queued = q.tasks.find(i);
      if (queued != q.tasks.end()) stuck.push_back(queued->second.job);  // queued, but can never start
    } else if (states[i].state != State::Done) {
      const auto queued = q.tasks.find(i);
      if (queued != q.tasks.end()) {
        const std::string array = queued->second.job.substr(0, queued->second.job.find('_'));
        activeArrays.insert(array);
        if (s.tasks[i].kind == TaskKind::Reference) activeReferences.insert(array);
      }
      if (queued == q.tasks.end() && states[i].state == State::Running && e.kind == "local")
        throw std::runtime_error("task " + s.tasks[i].id + " is running (" + states[i].detail + ")");
    }
  }
  activeJobs.assign(activeArrays.begin(), activeArrays.end());
  // Merge jobs of earlier submissions are replaced by the new one.
  for (const auto& m : q.merges) stuck.push_back(m.job);
  if (e.kind == "local" && !activeJobs.empty()) {
    throw std::runtime_error(
        std::to_string(activeJobs.size()) +
        " Slurm job array(s) of this sweep still have tasks queued or running: wait for them "
        "(`workbench sweep status DIR`) or scancel them, then resume");
  }
  if (!stuck.empty()) {
    std::string list;
    for (const auto& j : stuck) list += " " + j;
    std::printf("sweep: cancelling job(s) that can never start or are replaced:%s\n", list.c_str());
    cancelJobs(stuck);
  }
  writeExecutor(dir, e);
  std::printf("sweep %s: resuming %zu of %zu task(s)%s\n", s.name.c_str(), todo.size(), s.tasks.size(),
              activeJobs.empty() ? "" : " (others still queued or running in Slurm)");
  std::fflush(stdout);
  if (e.kind == "local") return finishLocal(dir, s, todo, e.jobs);
  return submit(dir, s, todo, e, again_.wait, {activeReferences.begin(), activeReferences.end()}, activeJobs);
}

}  // namespace wb::app
