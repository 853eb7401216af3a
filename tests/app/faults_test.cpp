// Faults, round 3 (issue 33), through the real `workbench` binary: a full disk, an unwritable folder, values
// that would make a run endless or wrong, environment variables, the inspector and a NaN, and the messages.
// Each test names the finding it covers.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/full_disk.h"
#include "../common/run_command.h"
#include "../common/temp_folder.h"
#include "../common/watch_log.h"
#include "common/paths.h"

namespace fs = std::filesystem;

namespace {

using wb::testing::CommandResult;
using wb::testing::readFile;
using wb::testing::writeFile;

// Commands that used to hang run under `timeout`: a hang fails the test (status 124) instead of stalling it.
CommandResult run(const std::string& args, const std::string& env = "") {
  return wb::testing::runCommand("env " + env + " timeout 300 " + std::string(WB_WORKBENCH_BIN) + " " + args);
}

fs::path tempDir(const std::string& name) {
  return wb::testing::tempFolder("wb_faults", name);
}

std::string box() {
  return (wb::sharedDir() / "assets/gltf/Box/glTF-Embedded/Box.gltf").string();
}

const std::string kSmall = " --size 16x16 --spp 1 ";

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// A private copy of shaders/ and assets/ (WB_ROOT) with its own shader cache.
fs::path privateRoot(const std::string& name) {
  const fs::path root = tempDir(name);
  fs::copy(wb::projectRoot() / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::copy(wb::projectRoot() / "assets", root / "assets", fs::copy_options::recursive);
  return root;
}

std::string rootEnv(const fs::path& root) {
  return "WB_ROOT=" + root.string() + " WB_SHADER_CACHE_DIR=" + (root / "cache").string();
}

}  // namespace

// 2. A full disk: every output is written whole or not at all. The previous files stay as they were, no
// temporary file is left, the command exits non-zero naming the file and the cause, and nothing says
// "rendered" (a truncated PNG was reported as rendered with exit status 0).
TEST(Faults, FullDiskKeepsTheOldFilesAndFailsTheRender) {
  const fs::path d = tempDir("full") / "disk";
  const fs::path elsewhere = tempDir("full_ok") / "ok.png";
  const std::string prepare = "for f in x.png x.exr s.json i.json; do echo \"old $f\" > \"$D/$f\"; done";
  const std::string body =
      "$WB render " + box() + kSmall + "--out \"$D/x.png\"; echo \"png=$?\"\n" +  //
      "$WB render " + box() + kSmall + "--out \"$D/x.exr\"; echo \"exr=$?\"\n" +  //
      "$WB render " + box() + kSmall + "--out " + elsewhere.string() +
      " --stats \"$D/s.json\"; echo \"stats=$?\"\n" + "$WB render " + box() + kSmall +
      "--inspect-pixel 1,1 --inspect-out \"$D/i.json\"; echo \"inspect=$?\"\n" +
      "for f in x.png x.exr s.json i.json; do echo \"content $f: $(cat \"$D/$f\")\"; done\n"
      "echo \"temporary files: $(ls -A \"$D\" | grep -c '\\.tmp\\.')\"\n";
  const auto r = wb::testing::runOnFullDisk(d, prepare, body, WB_WORKBENCH_BIN);
  const std::string& out = r.result.output;
  EXPECT_EQ(out.find("mount failed"), std::string::npos) << out;
  for (const char* step : {"png", "exr", "stats", "inspect"}) {
    EXPECT_NE(out.find(std::string(step) + "=1"), std::string::npos)
        << step << " (real disk " << r.realDisk << "): " << out;
  }
  for (const char* f : {"x.png", "x.exr", "s.json", "i.json"})
    EXPECT_NE(out.find(std::string("content ") + f + ": old " + f), std::string::npos) << f << ": " << out;
  EXPECT_NE(out.find("temporary files: 0"), std::string::npos) << out;
  EXPECT_EQ(out.find("rendered "), std::string::npos) << out;
  EXPECT_GE(count(out, "No space left on device (the disk is full)"), 4u) << out;
  EXPECT_NE(out.find("cannot write '" + (d / "x.png").string() + "'"), std::string::npos) << out;
  if (r.realDisk) {  // the simulated full disk fails every write, the image beside the stats too
    EXPECT_NE(out.find("--stats: cannot write '" + (d / "s.json").string() + "'"), std::string::npos) << out;
    EXPECT_NE(out.find("--inspect-out: cannot write"), std::string::npos) << out;
  }
}

// 2. converge on a full disk exited 0 with a 0-byte converge.md and error image, and said it wrote
// converge.csv when it could not. Now: exit 1, the old report untouched, no empty file.
TEST(Faults, FullDiskKeepsTheOldConvergeReport) {
  const fs::path d = tempDir("full_converge") / "disk";
  const std::string prepare = "echo 'old csv' > \"$D/converge.csv\"; echo 'old md' > \"$D/converge.md\"";
  const std::string body =
      "$WB converge --size 8x8 --seconds 0.05 --runs 1 --reference-spp 4 --config a: --out \"$D\"; "
      "echo \"converge=$?\"\n"
      "echo \"csv: $(cat \"$D/converge.csv\")\"; echo \"md: $(cat \"$D/converge.md\")\"\n"
      "echo \"empty files: $(find \"$D\" -type f -empty | wc -l)\"\n"
      "echo \"temporary files: $(ls -A \"$D\" | grep -c 'tmp')\"\n";
  const auto r = wb::testing::runOnFullDisk(d, prepare, body, WB_WORKBENCH_BIN);
  const std::string& out = r.result.output;
  EXPECT_NE(out.find("converge=1"), std::string::npos) << out;
  EXPECT_NE(out.find("csv: old csv"), std::string::npos) << out;
  EXPECT_NE(out.find("md: old md"), std::string::npos) << out;
  EXPECT_NE(out.find("empty files: 0"), std::string::npos) << out;
  EXPECT_NE(out.find("temporary files: 0"), std::string::npos) << out;
  // (The simulated full disk also fails the reference's cache file, before the report.)
  if (r.realDisk) {
    EXPECT_NE(out.find("cannot write '" + (d / "converge.csv").string() + "'"), std::string::npos) << out;
  }
  EXPECT_EQ(out.find("configuration(s) ->"), std::string::npos) << "said it wrote the report: " << out;
}

// 2. `watch --log` on a disk that takes no more bytes (/dev/full: every write fails with ENOSPC) lost every
// line silently. Now the first failure is said once on stderr, the reloads go on (stdout still has their
// lines) and the exit status says it. The same for --ab-diff-dir when its folder stops taking files during
// the session (it used to end watch at the next edit).
TEST(Faults, WatchOutputsThatFailSaySoOnceAndExitNonZero) {
  const fs::path root = privateRoot("watch_full");
  const fs::path out = root / "watch.out", pidFile = root / "watch.pid", diffs = root / "diffs";
  const std::string cmd = rootEnv(root) + " " + wb::testing::kOwnSession + "sh -c 'echo $$ > " +
                          pidFile.string() + "; exec " + WB_WORKBENCH_BIN +
                          " watch --headless --size 16x16 --log /dev/full --ab --ab-size 8x8 --ab-rounds 1 "
                          "--ab-diff-dir " +
                          diffs.string() + "' > " + out.string() + " 2>&1";
  FILE* proc = popen(cmd.c_str(), "r");
  ASSERT_NE(proc, nullptr);
  auto waitFor = [&](const std::function<bool(const std::string&)>& done) {
    const auto start = std::chrono::steady_clock::now();
    while (!done(readFile(out)) && std::chrono::steady_clock::now() - start < std::chrono::seconds(300))
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return done(readFile(out));
  };
  const bool started = waitFor([](const std::string& t) {
    return t.find("watching") != std::string::npos || t.find("error") != std::string::npos;
  });
  const pid_t pid = std::atoi(readFile(pidFile).c_str());
  bool stopped = false;
  bool immutable = false;
  auto stop = [&] {
    stopped = true;
    if (pid > 0) kill(pid, SIGINT);
    const int status = pclose(proc);
    if (immutable) wb::testing::runCommand("chattr -i '" + diffs.string() + "'");
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  };
  struct StopOnExit {
    std::function<void()> f;
    ~StopOnExit() { f(); }
  } stopOnExit{[&] {
    if (!stopped) stop();
  }};
  ASSERT_TRUE(started && readFile(out).find("watching") != std::string::npos) << readFile(out);
  // The folder stops taking files (the immutable attribute binds root too; skipped where the filesystem has
  // none).
  immutable = wb::testing::runCommand("chattr +i '" + diffs.string() + "'").code == 0;
  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  const std::string good = readFile(chit);
  const std::string needle = "const float minCos = 1e-3;";
  ASSERT_NE(good.find(needle), std::string::npos);
  for (const char* value : {"1.0001e-3", "1.0002e-3"}) {  // two real changes: two reload lines
    std::string edited = good;
    edited.replace(edited.find(needle), needle.size(), std::string("const float minCos = ") + value + ";");
    const size_t before = count(readFile(out), "\"pipelines_rebuilt\"");
    writeFile(chit, edited);
    ASSERT_TRUE(waitFor([&](const std::string& t) { return count(t, "\"pipelines_rebuilt\"") > before; }))
        << readFile(out);
  }
  const int code = stop();
  const std::string text = readFile(out);
  EXPECT_EQ(count(text, "--log: cannot append to '/dev/full': No space left on device"), 1u) << text;
  if (immutable) {
    EXPECT_EQ(count(text, "--ab-diff-dir: cannot write"), 1u) << text;
  }
  EXPECT_EQ(count(text, "\"pipelines_rebuilt\""), 2u) << "watch went on: " << text;
  EXPECT_EQ(code, 1) << text;
  fs::remove_all(root);
}

// 3. A --ab-diff-dir that exists but takes no files was accepted, and watch died at the first edit. Now it
// is refused at the start, like the other outputs.
TEST(Faults, UnwritableAbDiffDirIsRefusedAtTheStart) {
  const fs::path d = tempDir("ro_diff") / "diffs";
  const auto r = wb::testing::runOnFullDisk(
      d, "", "$WB watch --headless --size 16x16 --frames 1 --ab --ab-diff-dir \"$D\"; echo \"watch=$?\"",
      WB_WORKBENCH_BIN, wb::testing::Disk::ReadOnly);
  if (!r.realDisk) GTEST_SKIP() << "root without mount permission: no folder refuses root's writes here";
  const std::string& out = r.result.output;
  EXPECT_NE(out.find("watch=2"), std::string::npos) << out;
  EXPECT_NE(out.find("--ab-diff-dir: cannot write"), std::string::npos) << out;
  EXPECT_EQ(out.find("watching"), std::string::npos) << "started before refusing: " << out;
}

// 4. A script's outputs are checked before the window opens: a save to an unwritable path was silent (exit
// 0). Without a display the window renders headless, so this runs anywhere: the check comes first.
TEST(Faults, ScriptSaveToAnUnwritablePathIsRefusedFirst) {
  const fs::path dir = tempDir("script_save");
  writeFile(dir / "s.txt", "frames 1\nsave /proc/no/such/base\nquit\n");
  const auto r = run("--script " + (dir / "s.txt").string() + " --out " + (dir / "headless.png").string());
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find((dir / "s.txt").string() + ":2: save: cannot write '/proc/no/such/base.png'"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "headless.png")) << "rendered before refusing";
}

// 5. LP_NATIVE_VECTOR_WIDTH outside llvmpipe's widths segfaulted inside the driver (status 139).
TEST(Faults, LlvmpipeVectorWidthOutsideItsSetIsRefused) {
  const fs::path dir = tempDir("lp_width");
  for (const char* width : {"0", "64", "-1", "384", "0x80", "abc"}) {
    const auto r = run("render" + kSmall + "--out " + (dir / "x.png").string(),
                       std::string("LP_NATIVE_VECTOR_WIDTH=") + width);
    EXPECT_EQ(r.code, 2) << width << ": " << r.output;
    EXPECT_NE(r.output.find(std::string("LP_NATIVE_VECTOR_WIDTH=") + width + ": llvmpipe"), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("128, 256 or 512"), std::string::npos) << r.output;
  }
  const auto ok = run("render" + kSmall + "--out " + (dir / "x.png").string(),
                      "LP_NATIVE_VECTOR_WIDTH=256 MESA_SHADER_CACHE_DIR=" + (dir / "mesa").string());
  EXPECT_EQ(ok.code, 0) << ok.output;
}

// 6. Counts and durations that never end are refused when they enter (each of these ran forever).
TEST(Faults, RunsThatNeverEndAreRefused) {
  for (const std::string args :
       {"watch --headless --seconds nan", "watch --headless --seconds -5", "watch --headless --seconds 0",
        "watch --headless --seconds inf", "watch --headless --frames 0", "watch --headless --frames -1",
        "converge --seconds inf --reference-spp 4 --out /tmp/wb_never", "--frames 0"}) {
    const auto r = run(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
    const std::string flag = args.find("--seconds") != std::string::npos ? "--seconds" : "--frames";
    EXPECT_NE(r.output.find(flag + ":"), std::string::npos) << args << ": " << r.output;
  }
  EXPECT_FALSE(fs::exists("/tmp/wb_never"));
}

// 6. A script's frames and waits are finite and positive; a named pipe or a folder is no script (the pipe
// blocked forever, the folder ran as an empty script). All refused before any window or render.
TEST(Faults, ScriptsThatNeverEndAreRefused) {
  const fs::path dir = tempDir("script_never");
  const std::string out = " --out " + (dir / "headless.png").string();
  for (const std::string line : {"frames nan", "frames -1", "frames 0", "frames 1e9999", "wait_reload inf",
                                 "wait_samples 4 -1", "sleep nan"}) {
    writeFile(dir / "s.txt", "frames 1\n" + line + "\n");
    const auto r = run("--script " + (dir / "s.txt").string() + out);
    EXPECT_EQ(r.code, 2) << line << ": " << r.output;
    EXPECT_NE(r.output.find((dir / "s.txt").string() + ":2: " + line.substr(0, line.find(' '))),
              std::string::npos)
        << r.output;
  }
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  const auto fifo = run("--script " + (dir / "fifo").string() + out);
  EXPECT_EQ(fifo.code, 2) << fifo.output;
  EXPECT_NE(fifo.output.find("named pipe"), std::string::npos) << fifo.output;
  const auto folder = run("--script " + dir.string() + out);
  EXPECT_EQ(folder.code, 2) << folder.output;
  EXPECT_NE(folder.output.find("is a directory"), std::string::npos) << folder.output;
  EXPECT_FALSE(fs::exists(dir / "headless.png")) << "rendered before refusing";
}

// 6. converge stopped with Ctrl-C wrote nothing; now it writes the report of the checkpoints done, marked
// partial, and exits 128 + the signal (as render does).
TEST(Faults, InterruptedConvergeWritesAPartialReport) {
  const fs::path dir = tempDir("converge_interrupt");
  const fs::path report = dir / "report", log = dir / "log.txt";
  // Far longer than any test: the shell waits for the configuration's progress line (an event, with a
  // generous cap; it is printed after the first sample's checkpoint), then sends SIGINT as Ctrl-C would.
  const std::string script =
      "'" + std::string(WB_WORKBENCH_BIN) +
      "' converge --size 16x16 --seconds 100000 --runs 1 --reference-spp 4 --config a: "
      "--out '" +
      report.string() + "' > '" + log.string() +
      "' 2>&1 & pid=$!; "
      "for i in $(seq 6000); do grep -q 'a run 1' '" +
      log.string() +
      "' && break; kill -0 $pid 2>/dev/null || break; sleep 0.1; done; "
      "kill -INT $pid; wait $pid; echo \"exit=$?\"";
  writeFile(dir / "interrupt.sh", script + "\n");
  const auto r = wb::testing::runCommand("bash '" + (dir / "interrupt.sh").string() + "'");
  const std::string printed = readFile(log);
  EXPECT_NE(r.output.find("exit=130"), std::string::npos) << r.output << printed;
  const std::string md = readFile(report / "converge.md");
  EXPECT_NE(md.find("**Partial:** interrupted (signal 2) in configuration 'a'"), std::string::npos)
      << md << printed;
  std::ifstream csv(report / "converge.csv");
  std::string header, row;
  std::getline(csv, header);
  ASSERT_TRUE(static_cast<bool>(std::getline(csv, row))) << "no checkpoint row: " << printed;
  EXPECT_EQ(row.rfind("a,", 0), 0u) << row;
  EXPECT_NE(printed.find("partial, interrupted"), std::string::npos) << printed;
}

// 8. Values are checked where they enter: decimal numbers only, finite camera moves, one configuration per
// name, the command's flags outside configurations, and --inspect-samples bounded by what it writes.
TEST(Faults, WrongValuesAreRefused) {
  const fs::path dir = tempDir("values");
  const std::string png = " --out " + (dir / "x.png").string();
  const auto hex = run("render --mode hybrid --sun-angle 0x10" + kSmall + png);
  EXPECT_EQ(hex.code, 2) << hex.output;
  EXPECT_NE(hex.output.find("--sun-angle: '0x10' is not a finite decimal number"), std::string::npos)
      << hex.output;
  // A leading zero is decimal, not octal: --frames 010 renders 10 frames, not 8.
  const auto tenFrames = run("watch --headless --size 8x8 --frames 010");
  EXPECT_EQ(tenFrames.code, 0) << tenFrames.output;
  EXPECT_NE(tenFrames.output.find("watch: 10 frames"), std::string::npos) << tenFrames.output;
  const auto hexSpp = run("render --spp 0x10 --size 16x16" + png);
  EXPECT_EQ(hexSpp.code, 2) << hexSpp.output;
  for (const std::string line : {"orbit nan 0", "orbit 0 inf", "orbit 1e30 0"}) {
    writeFile(dir / "s.txt", line + "\n");
    const auto r = run("--script " + (dir / "s.txt").string() + png);
    EXPECT_EQ(r.code, 2) << line << ": " << r.output;
    EXPECT_NE(r.output.find(":1: orbit: D"), std::string::npos) << r.output;
  }
  const std::string base = "converge --size 8x8 --reference-spp 4 --out " + (dir / "c").string();
  for (const std::string configs : {"--config a: --config 'a:--no-nee'", "--config 'a b:' --config a_b:"}) {
    const auto r = run(base + " " + configs);
    EXPECT_EQ(r.code, 2) << configs << ": " << r.output;
    EXPECT_NE(r.output.find("give each its own name"), std::string::npos) << r.output;
  }
  for (const char* flag : {"--seconds 5", "--out x", "--reference r.exr", "--runs=2"}) {
    const auto r = run(base + " --config 'a:" + flag + "'");
    EXPECT_EQ(r.code, 2) << flag << ": " << r.output;
    EXPECT_NE(r.output.find("belongs to the command"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "c"));
  const std::string inspect = "render --inspect-pixel 1,1 --inspect-out " + (dir / "i.json").string();
  const auto tooMany = run(inspect + " --size 16x16 --spp 65536 --inspect-samples 65536");
  EXPECT_EQ(tooMany.code, 2) << tooMany.output;
  EXPECT_NE(tooMany.output.find("--inspect-samples: at most 3640 at --max-bounces 8"), std::string::npos)
      << tooMany.output;
  const auto fewerBounces =
      run(inspect + " --size 16x16 --spp 65536 --max-bounces 1 --inspect-samples 65536");
  EXPECT_NE(fewerBounces.output.find("at most 16384 at --max-bounces 1"), std::string::npos)
      << fewerBounces.output;
  const auto zero = run(inspect + " --size 16x16 --spp 4 --inspect-samples 0");
  EXPECT_EQ(zero.code, 2) << zero.output;
  EXPECT_NE(zero.output.find("--inspect-samples: at least 1"), std::string::npos) << zero.output;
}

// 9. A NaN written into the payload's radiance (an edit of closest-hit) is found at the vertex where it
// enters, and sum_of_added = radiance holds: the vertices' `added` are what raygen added, not what
// closest-hit recorded (they stayed finite, and first_non_finite pointed at the sample's sum).
TEST(Faults, InspectorFindsANanThePayloadCarries) {
  const fs::path root = privateRoot("inspect_nan");
  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  std::string text = readFile(chit);
  const std::string needle = "  payload.radiance = radiance;";
  ASSERT_NE(text.find(needle), std::string::npos);
  text.replace(text.find(needle), needle.size(),
               "  payload.radiance = radiance + vec3(uintBitsToFloat(0x7fc00000u));  // NaN");
  writeFile(chit, text);
  const fs::path json = root / "inspect.json";
  const auto r =
      run("render --size 16x16 --spp 2 --inspect-pixel 8,8 --inspect-out " + json.string(), rootEnv(root));
  ASSERT_EQ(r.code, 0) << r.output;
  const auto j = nlohmann::json::parse(readFile(json));
  ASSERT_EQ(j["samples"].size(), 2u);
  for (const auto& s : j["samples"]) {
    EXPECT_EQ(s["radiance"][0], "nan") << s.dump();
    EXPECT_EQ(s["sum_of_added"][0], "nan") << "sum_of_added = radiance: " << s.dump();
    ASSERT_FALSE(s["first_non_finite"].is_null()) << s.dump();
    EXPECT_EQ(s["first_non_finite"]["vertex"], 0) << s["first_non_finite"].dump();
    EXPECT_EQ(s["first_non_finite"]["term"], "added") << s["first_non_finite"].dump();
    ASSERT_FALSE(s["vertices"].empty());
    EXPECT_EQ(s["vertices"][0]["added"][0], "nan");
  }
  fs::remove_all(root);
}

// 10. Messages name the flag, the variable or the file, and flag errors exit 2 everywhere.
TEST(Faults, MessagesNameTheFlagTheVariableOrTheFile) {
  const fs::path dir = tempDir("messages");
  const std::string png = " --out " + (dir / "x.png").string();
  // A define whose value opens a comment: the error was at "-1:1", naming no flag.
  const std::string shader = (wb::projectRoot() / "shaders/pathtracer/miss.rmiss").string();
  for (const std::string define : {"'A=/*'", "'A=//'", "'A=x\\'", "'A=\"'"}) {
    const auto s = run("shaders --define " + define + " " + shader);
    EXPECT_EQ(s.code, 2) << define << ": " << s.output;
    EXPECT_NE(s.output.find("--define"), std::string::npos) << s.output;
    EXPECT_EQ(s.output.find("-1:"), std::string::npos) << s.output;
    const auto r = run("render --define " + define + kSmall + png);
    EXPECT_EQ(r.code, 2) << define << ": " << r.output;
  }
  // A define the shaders' preamble cannot take (here: it redefines the scene's specialisation) was reported
  // at
  // "-1:11", the preamble's line.
  const auto redefined = run("render --define WB_LIGHT_COUNT=7u" + kSmall + png);
  EXPECT_EQ(redefined.code, 1) << redefined.output;
  EXPECT_NE(redefined.output.find("in the define WB_LIGHT_COUNT=7u (--define"), std::string::npos)
      << redefined.output;
  EXPECT_EQ(redefined.output.find("-1:"), std::string::npos) << redefined.output;
  // converge --reference: plain reasons, and no empty --out folder left behind.
  const fs::path report = dir / "report";
  const auto rendered = run("render" + kSmall + "--out " + (dir / "ref16.exr").string());
  ASSERT_EQ(rendered.code, 0) << rendered.output;
  for (const auto& [ref, reason] : std::vector<std::pair<std::string, std::string>>{
           {(dir / "none.exr").string(), "no such file"},
           {(dir / "x.png").string(), "a PNG image, not OpenEXR"},
           {(dir / "ref16.exr").string(), "is 16x16, the render 32x32"}}) {
    if (ref.find("x.png") != std::string::npos) {
      ASSERT_EQ(run("render" + kSmall + png).code, 0);
    }
    const auto r = run("converge --size 32x32 --reference " + ref + " --out " + report.string());
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--reference"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(reason), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("code("), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(report)) << "an empty --out folder was left: " << r.output;
  }
  // WB_* variables with values they cannot take.
  for (const std::string env : {"WB_PIPELINE_LIBRARY=abc", "WB_JIT_WARMUP=banana", "WB_REBUILD_YIELD=-5",
                                "WB_VALIDATION=abc", "WB_REBUILD_YIELD=0x10", "WB_ROOT=abc"}) {
    const auto r = run("render" + kSmall + png, env);
    EXPECT_EQ(r.code, 2) << env << ": " << r.output;
    EXPECT_NE(r.output.find(env.substr(0, env.find('=')) + "="), std::string::npos)
        << env << ": " << r.output;
  }
  // A dangling shader_cache symbolic link.
  const fs::path cacheLink = dir / "cache_link";
  fs::create_symlink(dir / "gone", cacheLink);
  const auto dangling = run("render" + kSmall + png, "WB_SHADER_CACHE_DIR=" + cacheLink.string());
  EXPECT_EQ(dangling.code, 0) << dangling.output;
  EXPECT_NE(
      dangling.output.find("is a symbolic link to '" + (dir / "gone").string() + "', which does not exist"),
      std::string::npos)
      << dangling.output;
  EXPECT_EQ(dangling.output.find("File exists"), std::string::npos) << dangling.output;
  // watch: --ab-size errors exit 2, flags it has no use for are refused.
  for (const std::string& args :
       std::vector<std::string>{"--ab --ab-size 0x0", "--ab --ab-size banana", "--ab-size 32x32",
                                "--ab-rounds 3", "--ab-diff-dir " + (dir / "d").string(), "--aov albedo"}) {
    const auto r = run("watch --headless --frames 1 " + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
    EXPECT_EQ(r.output.find("watching"), std::string::npos) << args << ": " << r.output;
  }
  // An unknown script line is echoed truncated (a 5 MB line was echoed whole).
  writeFile(dir / "s.txt", std::string(5 << 20, 'z') + "\n");
  const auto longLine = run("--script " + (dir / "s.txt").string() + png);
  EXPECT_EQ(longLine.code, 2);
  EXPECT_LT(longLine.output.size(), 1000u);
  EXPECT_NE(longLine.output.find((dir / "s.txt").string() + ":1: unknown command 'zzz"), std::string::npos)
      << longLine.output.substr(0, 1000);
  EXPECT_NE(longLine.output.find("(5242880 bytes)"), std::string::npos) << longLine.output.substr(0, 1000);
}
