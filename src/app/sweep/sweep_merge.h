// The merge of a sweep: the usual converge report per scene (converge.csv, converge.png, converge.md with the
// efficiency table and the error images; app/converge_report.h) from the tasks' results, each configuration's
// seeds combined as converge combines its runs, and the sweep's own summary (DIR/report/summary.md and .json,
// tasks.csv): the spread over seeds, where the tasks ran and each task's start-up.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

#include "app/sweep/sweep_spec.h"

namespace wb::app::sweep {

struct MergeResult {
  std::vector<std::string> missing;  // tasks not done
  bool written = false;              // the report was written
  std::string message;               // what went wrong, when nothing was written
};

// Merges the tasks into DIR/report/. Refuses (nothing written) when a task is not done, unless `partial`:
// then the report leaves the missing tasks out and names them.
MergeResult mergeSweep(const std::filesystem::path& dir, const Sweep& s, bool partial);

// `workbench sweep merge DIR [--partial]`: prints the outcome; returns the exit status.
int runMerge(const std::filesystem::path& dir, bool partial);

}  // namespace wb::app::sweep
