// The Slurm executor: job scripts written into DIR/slurm/ (readable, and what Slurm runs), one job array for
// the reference renders, one array for the runs that starts once they all succeeded (afterok), and the merge
// as a last job after the runs. Every job submitted is recorded in DIR/slurm/jobs.json as soon as sbatch
// answers, so a shell killed between two submissions loses nothing that `sweep resume` cannot see.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "app/sweep/sweep_spec.h"
#include "app/sweep/sweep_state.h"

namespace wb::app::sweep {

struct Submission {
  std::vector<std::string> referenceJobs, runJobs;  // array job ids (an array per chunk of MaxArraySize)
  std::string mergeJob;
};

// Submits `tasks` (task numbers; references among them go first) and a merge job. Jobs of an earlier
// submission still queued or running are waited for (afterany; a task that needs a missing reference, and the
// merge, refuse clearly): `referenceJobs` (arrays holding reference renders) by the new runs, `activeJobs`
// (all of them) by the merge. Throws std::runtime_error with sbatch's message when a submission fails.
Submission submitToSlurm(const fs::path& dir, const Sweep& s, const std::vector<size_t>& tasks,
                         const Executor& e, const std::vector<std::string>& referenceJobs,
                         const std::vector<std::string>& activeJobs);

// Which of the sweep's jobs Slurm still has (squeue), per task and for the merge jobs. Queries nothing when
// the sweep has no Slurm jobs recorded.
QueueView queryQueue(const fs::path& dir, const Sweep& s);

// The job ids (array job ids and merge jobs) this sweep submitted, oldest first.
std::vector<std::string> recordedJobs(const fs::path& dir);

// scancel of these jobs or array elements; throws std::runtime_error when scancel fails.
void cancelJobs(const std::vector<std::string>& jobs);

// Runs a program (looked up in PATH) and returns its exit status and output (stdout and stderr).
struct CommandOutput {
  int status = -1;
  std::string output;
};
CommandOutput runProgram(const std::string& program, const std::vector<std::string>& args);

// A word for a shell script, quoted when it needs to be.
std::string shellQuote(const std::string& s);

}  // namespace wb::app::sweep
