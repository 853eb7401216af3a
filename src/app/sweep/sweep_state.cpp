#include "app/sweep/sweep_state.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <deque>
#include <fstream>

#include "common/file_io.h"
#include "common/json_text.h"

using nlohmann::json;

namespace wb::app::sweep {

fs::path taskDir(const fs::path& dir, const Task& t) {
  return dir / "tasks" / t.id;
}
fs::path resultFile(const fs::path& dir, const Task& t) {
  return taskDir(dir, t) / "result.json";
}
fs::path attemptFile(const fs::path& dir, const Task& t) {
  return taskDir(dir, t) / "attempt.json";
}
fs::path logFile(const fs::path& dir, const Task& t) {
  return taskDir(dir, t) / "log.txt";
}

fs::path checkpointImage(const fs::path& dir, const Task& t, uint32_t spp) {
  char name[32];
  std::snprintf(name, sizeof name, "spp_%06u.exr", spp);
  return taskDir(dir, t) / name;
}

fs::path referenceImage(const fs::path& dir, const Sweep& s, size_t scene) {
  if (!s.scenes.at(scene).referenceFile.empty()) return s.scenes[scene].referenceFile;
  return taskDir(dir, s.tasks.at(size_t(s.referenceTask(scene)))) / "reference.exr";
}

std::optional<json> readResult(const fs::path& dir, const Task& t) {
  const auto text = readRegularFile(resultFile(dir, t), nullptr, 64u << 20);
  if (!text) return std::nullopt;
  try {
    return json::parse(*text);
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

bool isDone(const fs::path& dir, const Task& t) {
  std::error_code ec;
  return fs::is_regular_file(resultFile(dir, t), ec);
}

FileLock::FileLock(const fs::path& path) {
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) return;
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

FileLock::~FileLock() {
  if (fd_ >= 0) ::close(fd_);
}

bool lockedElsewhere(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool busy = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return busy;
}

json toJson(const Executor& e) {
  return json{{"kind", e.kind}, {"jobs", e.jobs},         {"partition", e.partition},   {"gres", e.gres},
              {"time", e.time}, {"throttle", e.throttle}, {"sbatch_args", e.sbatchArgs}};
}

Executor executorFromJson(const json& j) {
  Executor e;
  e.kind = j.value("kind", "local");
  e.jobs = j.value("jobs", 0u);
  e.partition = j.value("partition", "");
  e.gres = j.value("gres", "");
  e.time = j.value("time", "");
  e.throttle = j.value("throttle", 0u);
  e.sbatchArgs = j.value("sbatch_args", std::vector<std::string>{});
  return e;
}

std::optional<Executor> readExecutor(const fs::path& dir) {
  const auto text = readRegularFile(dir / "executor.json", nullptr, 1u << 20);
  if (!text) return std::nullopt;
  try {
    return executorFromJson(json::parse(*text));
  } catch (const json::exception&) {
    return std::nullopt;
  }
}

void writeExecutor(const fs::path& dir, const Executor& e) {
  writeFileAtomically(dir / "executor.json", jsonText(toJson(e), 2) + "\n");
}

const char* stateName(State s) {
  switch (s) {
    case State::Pending:
      return "pending";
    case State::Running:
      return "running";
    case State::Done:
      return "done";
    case State::Failed:
      return "failed";
  }
  return "?";
}

std::vector<std::string> lastLines(const fs::path& path, size_t n) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return {};
  // Only the end of a long log is read.
  f.seekg(0, std::ios::end);
  const std::streamoff size = f.tellg();
  const std::streamoff start = size > 65536 ? size - 65536 : 0;
  f.seekg(start);
  std::deque<std::string> lines;
  for (std::string line; std::getline(f, line);) {
    // Progress lines rewritten in place end in carriage returns: keep what was shown last.
    const auto cr = line.find_last_of('\r', line.size() >= 2 ? line.size() - 2 : 0);
    if (cr != std::string::npos && cr + 1 < line.size()) line = line.substr(cr + 1);
    while (!line.empty() && (line.back() == '\r' || line.back() == '\n')) line.pop_back();
    if (line.empty()) continue;
    lines.push_back(line);
    if (lines.size() > n) lines.pop_front();
  }
  return {lines.begin(), lines.end()};
}

std::vector<TaskState> taskStates(const fs::path& dir, const Sweep& s, const QueueView& queue,
                                  size_t tailLines) {
  const bool localRun = lockedElsewhere(dir / "local.lock");
  std::vector<TaskState> out(s.tasks.size());
  for (size_t i = 0; i < s.tasks.size(); ++i) {
    const Task& t = s.tasks[i];
    TaskState& st = out[i];
    if (isDone(dir, t)) {
      st.state = State::Done;
      continue;
    }
    std::optional<json> attempt;
    if (const auto text = readRegularFile(attemptFile(dir, t), nullptr, 1u << 20)) {
      try {
        attempt = json::parse(*text);
      } catch (const json::exception&) {
      }
    }
    const auto queued = queue.tasks.find(i);
    if (queued != queue.tasks.end()) st.job = queued->second.job;
    if (lockedElsewhere(taskDir(dir, t) / "lock")) {
      st.state = State::Running;
      st.detail = "running";
      if (attempt)
        st.detail +=
            " on " + attempt->value("host", "?") + " (pid " + std::to_string(attempt->value("pid", 0)) + ")";
      if (!st.job.empty()) st.detail += ", job " + st.job;
      continue;
    }
    if (queued != queue.tasks.end() && queued->second.active()) {
      st.state = queued->second.state == "RUNNING" ? State::Running : State::Pending;
      st.detail = "job " + st.job + " in Slurm: " + queued->second.state + " (" + queued->second.reason + ")";
      continue;
    }
    if (!queue.error.empty() && !attempt) {
      st.state = State::Pending;  // Slurm may still hold it: what the queue says is not known
      st.detail = "not started yet; whether Slurm still holds it is not known (squeue failed)";
      continue;
    }
    if (queued != queue.tasks.end()) {
      st.state = State::Failed;
      st.detail =
          "job " + st.job + " can never start (" + queued->second.reason + ": a task it depends on failed)";
    } else if (localRun && !attempt) {
      st.state = State::Pending;
      st.detail = "waiting in the local run of this sweep";
      continue;
    } else if (attempt) {
      st.state = State::Failed;
      st.detail = "started on " + attempt->value("host", "?");
      if (!attempt->value("slurm_job", "").empty()) st.detail += " as job " + attempt->value("slurm_job", "");
      st.detail += ", ended without a result";
      st.job = attempt->value("slurm_job", st.job);
    } else {
      st.state = State::Failed;
      st.detail = "never started, and not queued (cancelled before it started, or its run was stopped)";
    }
    st.logTail = lastLines(logFile(dir, t), tailLines);
    // Slurm's own log of the job: what ended it (a cancel, a time limit) when the task could not say.
    if (attempt && !attempt->value("slurm_log", "").empty()) {
      for (auto& line : lastLines(attempt->value("slurm_log", ""), 2)) st.logTail.push_back("slurm: " + line);
    }
  }
  return out;
}

}  // namespace wb::app::sweep
