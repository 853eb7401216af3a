// `workbench watch` end to end: a private copy of shaders/ and assets/ (WB_ROOT), a real edit, a broken edit
// that keeps the last good pipeline rendering, and the fix that recovers.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"
#include "../common/watch_log.h"
#include "common/paths.h"

namespace fs = std::filesystem;

namespace {

using wb::testing::readFile;
using wb::testing::readLog;
using wb::testing::writeFile;

// Events are waited for with a generous cap (a busy machine makes a 1 s reload take tens of seconds), never
// for a fixed time.
constexpr double kEventCapSeconds = 300;

std::vector<nlohmann::json> waitForLog(const fs::path& p, size_t n, double seconds = kEventCapSeconds) {
  return wb::testing::waitForLog(p, n, seconds);
}

}  // namespace

TEST(Watch, EditBreakAndFixWhileRendering) {
  const fs::path root = fs::temp_directory_path() / ("wb_watch_" + std::to_string(::getpid()));
  fs::remove_all(root);
  fs::create_directories(root / "shader_cache");
  fs::copy(wb::projectRoot() / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::copy(wb::projectRoot() / "assets", root / "assets", fs::copy_options::recursive);
  const fs::path log = root / "reloads.jsonl", out = root / "watch.out", pidFile = root / "watch.pid";
  // No --seconds: the test stops it (SIGINT, by its process id) once every event it waits for has come, so a
  // slow machine only makes the test take longer. exec keeps the shell's pid for the workbench.
  const std::string cmd = "WB_ROOT=" + root.string() + " " + wb::testing::kOwnSession + "sh -c 'echo $$ > " +
                          pidFile.string() + "; exec " + WB_WORKBENCH_BIN +
                          " watch --headless --size 32x32 --log " + log.string() + "' > " + out.string() +
                          " 2>&1";
  FILE* proc = popen(cmd.c_str(), "r");
  ASSERT_NE(proc, nullptr);
  // Wait until it renders (the banner line is printed after the first pipeline exists).
  const auto started = std::chrono::steady_clock::now();
  while (readFile(out).find("watching") == std::string::npos &&
         std::chrono::steady_clock::now() - started < std::chrono::seconds(int(kEventCapSeconds)) &&
         readFile(out).find("error") == std::string::npos) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const pid_t pid = std::atoi(readFile(pidFile).c_str());
  bool stopped = false;
  auto stop = [&] {
    stopped = true;
    if (pid > 0) kill(pid, SIGINT);
    return pclose(proc);
  };
  // A failed assertion returns early: the watch process is stopped anyway.
  struct StopOnExit {
    std::function<void()> f;
    ~StopOnExit() { f(); }
  } stopOnExit{[&] {
    if (!stopped) stop();
  }};
  if (readFile(out).find("watching") == std::string::npos) {
    stop();
    FAIL() << readFile(out);
  }

  const fs::path chit = root / "shaders/pathtracer/closesthit.rchit";
  const std::string good = readFile(chit);
  // A real change (a comment alone changes no SPIR-V and rebuilds nothing).
  std::string edited = good;
  const std::string needle = "const float minCos = 1e-3;";
  ASSERT_NE(edited.find(needle), std::string::npos);
  edited.replace(edited.find(needle), needle.size(), "const float minCos = 1.0001e-3;");
  writeFile(chit, edited);
  auto lines = waitForLog(log, 1);
  ASSERT_GE(lines.size(), 1u) << readFile(out);
  EXPECT_TRUE(lines[0]["ok"].get<bool>()) << lines[0].dump();
  EXPECT_EQ(lines[0]["pipelines_rebuilt"], nlohmann::json::array({"pathtracer"}));
  EXPECT_TRUE(lines[0]["edit_to_first_frame_ms"].is_number());
  // The rest of the log line's contract: what changed, what was recompiled, and the times.
  ASSERT_EQ(lines[0]["files_changed"].size(), 1u) << lines[0].dump();
  EXPECT_NE(lines[0]["files_changed"][0].get<std::string>().find("closesthit.rchit"), std::string::npos);
  ASSERT_EQ(lines[0]["stages_recompiled"].size(), 1u)
      << "only the edited stage recompiles: " << lines[0].dump();
  EXPECT_NE(lines[0]["stages_recompiled"][0].get<std::string>().find("closesthit.rchit"), std::string::npos);
  EXPECT_GT(lines[0]["compile_ms"].get<double>(), 0.0);
  EXPECT_GT(lines[0]["pipeline_ms"].get<double>(), 0.0);
  EXPECT_GE(lines[0]["edit_to_new_pipeline_ms"].get<double>(), 0.0);
  // Frame times around the rebuild (null where there were no such frames: this edit may land during the very
  // first frame): the frames before, during, the first new one, and the control span before the edit.
  for (const char* key :
       {"frame_ms_median_before", "frame_ms_max_during_rebuild", "frame_ms_max_before_same_span"}) {
    EXPECT_TRUE(lines[0][key].is_null() || lines[0][key].get<double>() > 0.0)
        << key << ": " << lines[0].dump();
  }
  EXPECT_TRUE(lines[0]["frames_during_rebuild"].is_number()) << lines[0].dump();
  EXPECT_GT(lines[0]["first_new_frame_ms"].get<double>(), 0.0) << lines[0].dump();
  // Linked pipelines' libraries: a GPU compiles only the hit group's; lavapipe builds monolithic pipelines.
  for (const char* key : {"pipeline_libraries_compiled", "pipeline_libraries_reused", "pipeline_library_ms",
                          "pipeline_link_ms"})
    EXPECT_TRUE(lines[0][key].is_number()) << key << ": " << lines[0].dump();
  const auto libraries = std::make_pair(lines[0]["pipeline_libraries_compiled"].get<int>(),
                                        lines[0]["pipeline_libraries_reused"].get<int>());
  EXPECT_TRUE(libraries == std::make_pair(0, 0) || libraries == std::make_pair(1, 3))
      << "monolithic, or linked with only the edited hit group's library new: " << lines[0].dump();

  // A syntax error on line 3: reported with file:line, the old pipeline keeps rendering.
  std::string broken = good;
  broken.insert(broken.find('\n', broken.find('\n') + 1) + 1, "this is not glsl;\n");
  writeFile(chit, broken);
  lines = waitForLog(log, 2);
  ASSERT_GE(lines.size(), 2u) << readFile(out);
  EXPECT_FALSE(lines[1]["ok"].get<bool>());
  EXPECT_NE(lines[1]["error"].get<std::string>().find("closesthit.rchit:3:"), std::string::npos)
      << lines[1].dump();
  EXPECT_TRUE(lines[1]["pipelines_rebuilt"].empty());

  writeFile(chit, good);
  lines = waitForLog(log, 3);
  ASSERT_GE(lines.size(), 3u) << readFile(out);
  EXPECT_TRUE(lines[2]["ok"].get<bool>()) << lines[2].dump();
  EXPECT_EQ(lines[2]["pipelines_rebuilt"], nlohmann::json::array({"pathtracer"}));

  // Bytes that are not UTF-8 (random data saved over the shader): a failed reload with the error logged, the
  // old pipeline rendering; the log line is JSON with the bytes replaced (nlohmann threw type_error.316 here
  // and watch exited).
  std::string junk = "\x80";  // glslang reports it as the unexpected token: the error text holds it
  for (int i = 0; i < 4096; ++i) junk += static_cast<char>((i * 7919 + 13) % 251 + 3);
  writeFile(chit, junk);
  lines = waitForLog(log, 4);
  ASSERT_GE(lines.size(), 4u) << readFile(out);
  EXPECT_FALSE(lines[3]["ok"].get<bool>()) << lines[3].dump();
  EXPECT_NE(lines[3]["error"].get<std::string>().find("closesthit.rchit:"), std::string::npos)
      << lines[3].dump();
  writeFile(chit, good);
  lines = waitForLog(log, 5);
  ASSERT_GE(lines.size(), 5u) << readFile(out);
  EXPECT_TRUE(lines[4]["ok"].get<bool>()) << lines[4].dump();

  // A resource the path tracer does not bind (set 0, binding 30), declared and used: a reload error at its
  // declaration, the old pipeline kept (it used to be accepted, and traced with an unbound descriptor).
  std::string extra = good;
  const size_t afterIncludes = extra.find('\n', extra.rfind("#include")) + 1;
  extra.insert(afterIncludes,
               "layout(set = 0, binding = 30, std430) buffer WbExtra { vec4 v[]; } wbExtra;\n");
  extra.insert(extra.find('\n', extra.find("void main()")) + 1, "  if (wbExtra.v[0].x > 1e30) return;\n");
  const int declarationLine = 1 + int(std::count(good.begin(), good.begin() + long(afterIncludes), '\n'));
  writeFile(chit, extra);
  lines = waitForLog(log, 6);
  ASSERT_GE(lines.size(), 6u) << readFile(out);
  EXPECT_FALSE(lines[5]["ok"].get<bool>()) << lines[5].dump();
  EXPECT_TRUE(lines[5]["pipelines_rebuilt"].empty()) << lines[5].dump();
  const std::string error = lines[5]["error"].get<std::string>();
  EXPECT_NE(error.find("closesthit.rchit:" + std::to_string(declarationLine) + ": error: set 0 binding 30"),
            std::string::npos)
      << error;
  writeFile(chit, good);
  lines = waitForLog(log, 7);
  ASSERT_GE(lines.size(), 7u) << readFile(out);
  EXPECT_TRUE(lines[6]["ok"].get<bool>()) << lines[6].dump();

  const int status = stop();
  EXPECT_EQ(WEXITSTATUS(status), 0) << readFile(out);
  // Exactly one reload per save, and frames kept coming throughout.
  EXPECT_EQ(readLog(log).size(), 7u);
  const std::string text = readFile(out);
  unsigned long long frames = 0;
  size_t reloads = 0;
  ASSERT_EQ(std::sscanf(text.substr(text.find("watch: ")).c_str(), "watch: %llu frames, %zu reloads", &frames,
                        &reloads),
            2)
      << text;
  EXPECT_EQ(reloads, 7u);
  EXPECT_GT(frames, 20u);
  fs::remove_all(root);
}
