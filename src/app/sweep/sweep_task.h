// One task of a sweep, run in its own process (`workbench sweep run-task DIR ID`) wherever an executor starts
// it: a reference render, or one run (scene, configuration, seed) through the sweep's checkpoints. Its seed
// and samples depend only on the task, so it makes the same images on any machine with the same device and
// driver. It writes into DIR/tasks/ID/ only, its result.json last.
#pragma once
#include <filesystem>
#include <string>

namespace wb::app::sweep {

// Runs the task named by its id or number. A task already done is not run again unless `force`. Returns the
// exit status (0 done; 1 failed, with the reason on stderr).
int runTask(const std::filesystem::path& dir, const std::string& task, bool force);

}  // namespace wb::app::sweep
