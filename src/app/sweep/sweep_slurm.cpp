#include "app/sweep/sweep_slurm.h"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "app/process.h"
#include "common/file_io.h"
#include "common/json_text.h"

using nlohmann::json;

namespace wb::app::sweep {
namespace {

std::string nowText() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S%z", std::localtime(&t));
  return buf;
}

json readJobs(const fs::path& dir) {
  const auto text = readRegularFile(dir / "slurm" / "jobs.json", nullptr, 256u << 20);
  if (!text) return json{{"submissions", json::array()}};
  try {
    return json::parse(*text);
  } catch (const json::exception&) {
    throw std::runtime_error((dir / "slurm" / "jobs.json").string() + ": not valid JSON");
  }
}

// Slurm's limit on array indices (MaxArraySize; indices go up to one less). 1001 is Slurm's default.
size_t maxArraySize() {
  const CommandOutput out = runProgram("scontrol", {"show", "config"});
  if (out.status == 0) {
    std::istringstream in(out.output);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("MaxArraySize", 0) != 0) continue;
      const auto eq = line.find('=');
      if (eq == std::string::npos) break;
      try {
        const long v = std::stol(line.substr(eq + 1));
        if (v > 1) return size_t(v);
      } catch (const std::exception&) {
      }
    }
  }
  return 1001;
}

// A #SBATCH line cannot quote: paths in one must be plain.
void requirePlainPath(const fs::path& p) {
  for (char c : p.string()) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '"' || c == '\'' || c == '\\' || c == '%') {
      throw std::runtime_error(
          "--out: '" + p.string() +
          "' has blanks, quotes or %: Slurm job scripts cannot name it in #SBATCH lines");
    }
  }
}

std::string sbatchHeader(const std::string& jobName, const fs::path& dir, const std::string& output,
                         const Executor& e, bool gpu) {
  std::string h;
  h += "#SBATCH --job-name=" + jobName + "\n";
  h += "#SBATCH --chdir=" + dir.string() + "\n";
  h += "#SBATCH --output=" + (dir / "slurm" / "logs" / output).string() + "\n";
  h += "#SBATCH --ntasks=1\n";
  if (!e.partition.empty()) h += "#SBATCH --partition=" + e.partition + "\n";
  if (gpu && !e.gres.empty()) h += "#SBATCH --gres=" + e.gres + "\n";
  if (!e.time.empty()) h += "#SBATCH --time=" + e.time + "\n";
  for (const auto& a : e.sbatchArgs) h += "#SBATCH " + a + "\n";
  return h;
}

void writeScripts(const fs::path& dir, const Sweep& s, const Executor& e) {
  const std::string wb = shellQuote(selfExecutable());
  const std::string d = shellQuote(dir.string());
  {
    std::ofstream f(dir / "slurm" / "task.sbatch");
    f << "#!/bin/bash\n"
         "# One task of the sweep in "
      << dir.string()
      << " per array element, written by `workbench sweep` (docs/sweeps.md).\n"
         "# The list file given as the argument names the task of element N on its line N + 1 (its number\n"
         "# and id); the task writes everything into tasks/ID/ (its output: tasks/ID/log.txt).\n"
      << sbatchHeader("wb-" + s.name, dir, "%A_%a.out", e, true)
      << "set -eu\n"
         "line=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" \"$1\")\n"
         "id=${line#* }\n"
         "mkdir -p "
      << d << "/tasks/\"$id\"\n"
      << "exec " << wb << " sweep run-task " << d << " \"$id\" > " << d << "/tasks/\"$id\"/log.txt 2>&1\n";
  }
  {
    std::ofstream f(dir / "slurm" / "merge.sbatch");
    f << "#!/bin/bash\n"
         "# The merge of the sweep in "
      << dir.string()
      << " once its tasks are done, written by `workbench sweep` (docs/sweeps.md): the report goes to "
         "report/.\n"
      << sbatchHeader("wb-" + s.name + "-merge", dir, "merge_%j.out", e, false) << "exec " << wb
      << " sweep merge " << d << "\n";
  }
}

std::string joinIds(const std::vector<std::string>& ids) {
  std::string out;
  for (const auto& id : ids) out += ":" + id;
  return out;
}

// "afterok:1:2,afterany:3" (every part must hold); empty when there is nothing to wait for.
std::string dependency(const std::vector<std::string>& ok, const std::vector<std::string>& any) {
  std::string d;
  if (!ok.empty()) d += "afterok" + joinIds(ok);
  if (!any.empty()) d += (d.empty() ? "" : ",") + std::string("afterany") + joinIds(any);
  return d;
}

class Submitter {
 public:
  Submitter(const fs::path& dir, const Sweep& s, const Executor& e) : dir_(dir), sweep_(s), exec_(e) {
    jobs_ = readJobs(dir);
    number_ = jobs_["submissions"].size() + 1;
    jobs_["submissions"].push_back(json{{"number", number_}, {"time", nowText()}, {"arrays", json::array()}});
  }

  // Submits `tasks` as arrays of at most MaxArraySize elements; returns their job ids.
  std::vector<std::string> arrays(const std::vector<size_t>& tasks, const std::string& kind,
                                  const std::string& dep, size_t chunk) {
    std::vector<std::string> ids;
    for (size_t first = 0, k = 0; first < tasks.size(); first += chunk, ++k) {
      const size_t n = std::min(chunk, tasks.size() - first);
      const std::string list =
          "lists/" + std::to_string(number_) + "-" + kind + "-" + std::to_string(k) + ".txt";
      {
        std::ofstream f(dir_ / "slurm" / list);
        for (size_t i = first; i < first + n; ++i) f << tasks[i] << " " << sweep_.tasks[tasks[i]].id << "\n";
        if (!f.flush()) throw std::runtime_error("cannot write " + (dir_ / "slurm" / list).string());
      }
      std::string array = "--array=0-" + std::to_string(n - 1);
      if (exec_.throttle > 0) array += "%" + std::to_string(exec_.throttle);
      std::vector<std::string> args = {"--parsable", array};
      if (!dep.empty()) args.push_back("--dependency=" + dep);
      args.push_back((dir_ / "slurm" / "task.sbatch").string());
      args.push_back((dir_ / "slurm" / list).string());
      const std::string id = sbatch(args);
      ids.push_back(id);
      json entry{{"job", id}, {"kind", kind}, {"list", list}, {"tasks", json::array()}};
      for (size_t i = first; i < first + n; ++i) entry["tasks"].push_back(tasks[i]);
      jobs_["submissions"].back()["arrays"].push_back(entry);
      save();
    }
    return ids;
  }

  std::string merge(const std::string& dep) {
    std::vector<std::string> args = {"--parsable"};
    if (!dep.empty()) args.push_back("--dependency=" + dep);
    args.push_back((dir_ / "slurm" / "merge.sbatch").string());
    const std::string id = sbatch(args);
    jobs_["submissions"].back()["merge"] = id;
    save();
    return id;
  }

 private:
  std::string sbatch(const std::vector<std::string>& args) {
    std::string line = "sbatch";
    for (const auto& a : args) line += " " + shellQuote(a);
    const CommandOutput out = runProgram("sbatch", args);
    std::ofstream(dir_ / "slurm" / "submit.log", std::ios::app)
        << nowText() << " " << line << "\n  -> exit " << out.status << ": " << out.output;
    std::string id = out.output;
    // --parsable prints "jobid" or "jobid;cluster" (after any warnings, on the last line).
    while (!id.empty() && (id.back() == '\n' || id.back() == '\r')) id.pop_back();
    if (const auto nl = id.find_last_of('\n'); nl != std::string::npos) id = id.substr(nl + 1);
    if (const auto semi = id.find(';'); semi != std::string::npos) id = id.substr(0, semi);
    const bool numeric = !id.empty() && id.find_first_not_of("0123456789") == std::string::npos;
    if (out.status != 0 || !numeric) {
      throw std::runtime_error("sbatch failed (exit " + std::to_string(out.status) + "): " + out.output +
                               "the command: " + line);
    }
    return id;
  }

  void save() { writeFileAtomically(dir_ / "slurm" / "jobs.json", jsonText(jobs_, 1) + "\n"); }

  fs::path dir_;
  const Sweep& sweep_;
  Executor exec_;
  json jobs_;
  size_t number_ = 0;
};

}  // namespace

std::string shellQuote(const std::string& s) {
  if (!s.empty() &&
      s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./:=,+@%") ==
          std::string::npos) {
    return s;
  }
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

CommandOutput runProgram(const std::string& program, const std::vector<std::string>& args) {
  CommandOutput out;
  if (program.find('/') == std::string::npos && findProgram(program).empty()) {
    out.status = 127;
    out.output = program + ": not found in PATH\n";
    return out;
  }
  static std::atomic<unsigned> counter{0};
  const fs::path log = fs::temp_directory_path() /
                       ("wb-sweep-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".out");
  try {
    ChildProcess child = ChildProcess::spawn(program, args, {}, log.string());
    out.status = child.wait();
  } catch (const std::exception& e) {
    out.status = 127;
    out.output = std::string(e.what()) + "\n";
    return out;
  }
  out.output = readRegularFile(log).value_or("");
  std::error_code ec;
  fs::remove(log, ec);
  return out;
}

Submission submitToSlurm(const fs::path& dirIn, const Sweep& s, const std::vector<size_t>& tasks,
                         const Executor& e, const std::vector<std::string>& referenceJobs,
                         const std::vector<std::string>& activeJobs) {
  std::error_code ec;
  const fs::path dir = fs::absolute(dirIn, ec).lexically_normal();
  requirePlainPath(dir);
  if (findProgram("sbatch").empty()) {
    throw std::runtime_error(
        "--slurm: sbatch is not in PATH (run on a Slurm login node; scripts/slurm-local.sh start makes a "
        "single-node cluster on this machine)");
  }
  fs::create_directories(dir / "slurm" / "lists");
  fs::create_directories(dir / "slurm" / "logs");
  writeScripts(dir, s, e);
  std::vector<size_t> refs, runs;
  for (size_t t : tasks) (s.tasks.at(t).kind == TaskKind::Reference ? refs : runs).push_back(t);
  const size_t chunk = maxArraySize();
  Submitter sub(dir, s, e);
  Submission out;
  out.referenceJobs = sub.arrays(refs, "ref", "", chunk);
  out.runJobs = sub.arrays(runs, "run", dependency(out.referenceJobs, referenceJobs), chunk);
  std::vector<std::string> all = out.referenceJobs;
  all.insert(all.end(), out.runJobs.begin(), out.runJobs.end());
  out.mergeJob = sub.merge(dependency(all, activeJobs));
  return out;
}

std::vector<std::string> recordedJobs(const fs::path& dir) {
  std::vector<std::string> ids;
  const json jobs = readJobs(dir);
  for (const auto& sub : jobs["submissions"]) {
    for (const auto& a : sub["arrays"]) ids.push_back(a.value("job", ""));
    if (sub.contains("merge")) ids.push_back(sub.value("merge", ""));
  }
  return ids;
}

QueueView queryQueue(const fs::path& dir, const Sweep& s) {
  QueueView view;
  const json jobs = readJobs(dir);
  std::map<std::string, std::vector<size_t>> arrays;  // array job id -> task numbers by element
  std::map<std::string, bool> merges;
  for (const auto& sub : jobs["submissions"]) {
    for (const auto& a : sub["arrays"]) arrays[a.value("job", "")] = a.value("tasks", std::vector<size_t>{});
    if (sub.contains("merge")) merges[sub.value("merge", "")] = true;
  }
  if (arrays.empty() && merges.empty()) return view;
  view.queried = true;
  const CommandOutput out = runProgram("squeue", {"-h", "-r", "--me", "-o", "%F|%K|%T|%r"});
  if (out.status != 0) {
    view.error = "squeue failed (exit " + std::to_string(out.status) + "): " + out.output;
    return view;
  }
  std::istringstream in(out.output);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string part; std::getline(ss, part, '|');) f.push_back(part);
    if (f.size() < 4) continue;
    QueuedJob q;
    q.state = f[2];
    q.reason = f[3];
    if (const auto a = arrays.find(f[0]); a != arrays.end()) {
      size_t element = 0;
      try {
        element = std::stoul(f[1]);
      } catch (const std::exception&) {
        continue;  // an array line that was not split (N/A or a range)
      }
      if (element >= a->second.size() || a->second[element] >= s.tasks.size()) continue;
      q.job = f[0] + "_" + f[1];
      view.tasks[a->second[element]] = q;
    } else if (merges.count(f[0])) {
      q.job = f[0];
      view.merges.push_back(q);
    }
  }
  return view;
}

void cancelJobs(const std::vector<std::string>& jobs) {
  if (jobs.empty()) return;
  const CommandOutput out = runProgram("scancel", jobs);
  if (out.status != 0)
    throw std::runtime_error("scancel failed (exit " + std::to_string(out.status) + "): " + out.output);
}

}  // namespace wb::app::sweep
