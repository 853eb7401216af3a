// A full disk, or a folder nothing can be written to, for the tests of outputs: a bash script runs with $D, a
// folder on such a disk, and $WB, the prefix of a workbench command line there.
//
// Where the test may mount (root, as in CI): $D is a 64 KiB tmpfs mounted in a mount namespace of the
// script's own (`unshare -m`): the mount exists only while the script runs and is never seen outside it, so
// nothing is left behind, whatever happens to the test. `prepare` runs first (it writes the files that must
// survive), then a filler file (.filler) takes every free byte, or the tmpfs is remounted read-only.
// Elsewhere $D is an ordinary folder: for a full disk $WB sets WB_SIMULATE_DISK_FULL=1, which makes the
// workbench's writes fail as on a full disk (common/atomic_file.cpp); a read-only folder gets the immutable
// attribute (chattr +i, removed after the body) or, for a user other than root, mode 555 (realDisk says
// whether the folder really refused writes).
#pragma once
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "run_command.h"

namespace wb::testing {

struct FullDiskRun {
  CommandResult result;
  // Full: a tmpfs was mounted (else the write failures were simulated). ReadOnly: the folder really refuses
  // writes (a read-only mount, the immutable attribute, or a mode that binds a user other than root).
  bool realDisk = false;
};

// Whether this process may mount a tmpfs in a mount namespace of its own (asked once). WB_TEST_NO_MOUNT=1
// takes the other way, to run the tests as where no mount is permitted.
inline bool canMountTmpfs() {
  static const bool can = [] {
    if (const char* no = std::getenv("WB_TEST_NO_MOUNT"); no && std::string(no) == "1") return false;
    const std::filesystem::path probe =
        std::filesystem::temp_directory_path() / ("wb_mount_probe_" + std::to_string(::getpid()));
    std::filesystem::create_directories(probe);
    const auto r = runCommand("unshare -m --propagation private sh -c 'mount -t tmpfs -o size=4k tmpfs " +
                              probe.string() + "' 2>/dev/null");
    std::error_code ec;
    std::filesystem::remove(probe, ec);
    return r.code == 0;
  }();
  return can;
}

enum class Disk { Full, ReadOnly };

// Runs `body` (bash) with $D at `dir` (created; on a tmpfs what the script writes goes with the mount). What
// the script prints is the result's output.
inline FullDiskRun runOnFullDisk(const std::filesystem::path& dir, const std::string& prepare,
                                 const std::string& body, const std::string& workbench,
                                 Disk disk = Disk::Full) {
  FullDiskRun run;
  const bool mount = canMountTmpfs();
  std::filesystem::create_directories(dir);
  const std::filesystem::path script = dir.parent_path() / (dir.filename().string() + ".sh");
  std::ofstream s(script);
  s << "set -u\nD='" << dir.string() << "'\n";
  if (mount) s << "mount -t tmpfs -o size=64k tmpfs \"$D\" || { echo 'mount failed'; exit 97; }\n";
  s << prepare << "\n";
  if (disk == Disk::Full && mount) s << "dd if=/dev/zero of=\"$D/.filler\" bs=4096 2>/dev/null\n";
  if (disk == Disk::ReadOnly && mount) s << "mount -o remount,ro \"$D\" && echo 'read-only: mount'\n";
  if (disk == Disk::ReadOnly && !mount) {
    // Without a mount: the immutable attribute binds root too (where the filesystem has it), else a mode.
    s << "if chattr +i \"$D\" 2>/dev/null; then echo 'read-only: chattr'; "
         "elif [ \"$(id -u)\" != 0 ]; then chmod 555 \"$D\"; echo 'read-only: chmod'; fi\n";
  }
  const bool simulate = disk == Disk::Full && !mount;
  s << "WB='" << (simulate ? "env WB_SIMULATE_DISK_FULL=1 " : "") << workbench << "'\n";
  s << body << "\n";
  if (disk == Disk::ReadOnly && !mount) s << "chattr -i \"$D\" 2>/dev/null; chmod 755 \"$D\"\n";
  s.close();
  run.result =
      runCommand((mount ? "unshare -m --propagation private bash '" : "bash '") + script.string() + "'");
  run.realDisk = disk == Disk::Full ? mount : run.result.output.find("read-only: ") != std::string::npos;
  std::error_code ec;
  std::filesystem::remove(script, ec);
  return run;
}

}  // namespace wb::testing
