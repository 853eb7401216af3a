// `workbench sweep`: convergence studies too large for one `converge` run, as independent tasks run locally
// or as Slurm job arrays (docs/sweeps.md).
//
//   workbench sweep SPEC (--local [-j N] | --slurm [--wait] [--partition P] [--gres G] [--time T]
//                         [--throttle K] [--sbatch-arg ARG]...) --out DIR
//   workbench sweep status DIR [--json] [--all]
//   workbench sweep resume DIR [--local [-j N] | --slurm [...]] [--wait]
//   workbench sweep merge DIR [--partial]
//   workbench sweep run-task DIR TASK [--force]      (what the executors run: one task)
#pragma once
#include <string>

#include "app/command.h"
#include "app/sweep/sweep_state.h"

namespace wb::app {

class SweepCommand : public Command {
 public:
  const char* name() const override { return "sweep"; }
  const char* description() const override {
    return "Run a sweep (scenes x configurations x seeds) as tasks, here or as Slurm job arrays, and merge "
           "the report";
  }
  void addFlags(CLI::App& app) override;
  void finish() override;
  int run() override;

  // The executor's flags, on `sweep` and on `sweep resume`.
  struct ExecutorFlags {
    bool local = false, slurm = false, wait = false;
    unsigned jobs = 0;
    std::string partition, gres, time;
    unsigned throttle = 0;
    std::vector<std::string> sbatchArgs;
    CLI::Option* jobsOption = nullptr;
    std::vector<CLI::Option*> slurmOptions;
  };

 private:
  int create();
  int status();
  int resume();
  sweep::Executor executor(const ExecutorFlags& f, const sweep::Executor& fallback) const;

  CLI::App *status_ = nullptr, *resume_ = nullptr, *merge_ = nullptr, *runTask_ = nullptr;
  std::string spec_, out_, dir_, task_;
  ExecutorFlags create_, again_;
  bool json_ = false, all_ = false, partial_ = false, force_ = false;
};

}  // namespace wb::app
