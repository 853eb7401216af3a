// `render` interrupted with Ctrl-C (SIGINT) writes the image accumulated so far, with its stats marked
// partial, and exits with 128 + the signal; its progress lines say how far it got. One that dies of a fatal
// signal (SIGABRT: what a driver's compiler raises when it fails) says so with its call stack first.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"

namespace fs = std::filesystem;

namespace {

// A render far longer than any test (48x32, a million samples, writing `out`) in folder `dir`, sent `signal`
// by the shell once its first progress line is there (an event, with a generous cap). Returns the shell's
// "exit=<status>" line and what the render printed.
std::pair<std::string, std::string> renderThenSignal(const fs::path& dir, const fs::path& out,
                                                     const std::string& signal) {
  const fs::path log = dir / "log.txt", scriptFile = dir / "signal.sh";
  const std::string script = "'" + std::string(WB_WORKBENCH_BIN) +
                             "' render --size 48x32 --spp 1000000 --out '" + out.string() + "' --stats '" +
                             (dir / "partial.json").string() + "' > '" + log.string() +
                             "' 2>&1 & pid=$!; "
                             "for i in $(seq 6000); do grep -q 'ETA' '" +
                             log.string() +
                             "' && break; kill -0 $pid 2>/dev/null || break; sleep 0.1; done; "
                             "kill -" +
                             signal + " $pid; wait $pid; echo \"exit=$?\"";
  std::ofstream(scriptFile) << script << "\n";
  const auto r = wb::testing::runCommand("bash '" + scriptFile.string() + "'");
  std::ifstream lf(log);
  return {r.output, std::string((std::istreambuf_iterator<char>(lf)), {})};
}

fs::path freshFolder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / (name + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

TEST(Interrupt, CtrlCWritesThePartialImageWithItsStatsMarkedPartial) {
  const fs::path dir = freshFolder("wb_interrupt_");
  const fs::path out = dir / "partial.png", stats = dir / "partial.json";
  // SIGINT, as Ctrl-C sends it.
  const auto [exitLine, printed] = renderThenSignal(dir, out, "INT");
  EXPECT_NE(exitLine.find("exit=130"), std::string::npos) << exitLine << printed;
  EXPECT_NE(printed.find("render: "), std::string::npos) << "a progress line: " << printed;
  EXPECT_NE(printed.find("partial"), std::string::npos) << printed;
  ASSERT_TRUE(fs::exists(out)) << printed;
  EXPECT_GT(fs::file_size(out), 0u);
  std::ifstream sf(stats);
  ASSERT_TRUE(sf.good()) << printed;
  const auto j = nlohmann::json::parse(sf);
  EXPECT_TRUE(j["partial"].get<bool>());
  EXPECT_GE(j["spp"].get<int>(), 1);
  EXPECT_LT(j["spp"].get<int>(), 1000000);
  EXPECT_EQ(j["spp_requested"].get<int>(), 1000000);
  fs::remove_all(dir);
}

TEST(Interrupt, AFatalSignalPrintsTheThreadAndTheCallStack) {
  const fs::path dir = freshFolder("wb_abort_");
  const auto [exitLine, printed] = renderThenSignal(dir, dir / "never.png", "ABRT");
  EXPECT_NE(exitLine.find("exit=134"), std::string::npos) << exitLine << printed;
  EXPECT_NE(printed.find("*** workbench: fatal signal 6 (ABRT) in thread "), std::string::npos) << printed;
  EXPECT_NE(printed.find("its call stack:\n"), std::string::npos) << printed;
  fs::remove_all(dir);
}
