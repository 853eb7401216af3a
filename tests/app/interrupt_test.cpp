// `render` interrupted with Ctrl-C (SIGINT) writes the image accumulated so far, with its stats marked
// partial, and exits with 128 + the signal; its progress lines say how far it got. One that dies of a fatal
// signal (SIGABRT: what a driver's compiler raises when it fails) says so with its call stack first.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "../common/run_command.h"

namespace fs = std::filesystem;

TEST(Interrupt, CtrlCWritesThePartialImageWithItsStatsMarkedPartial) {
  const fs::path dir = fs::temp_directory_path() / ("wb_interrupt_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "partial.png", stats = dir / "partial.json", log = dir / "log.txt";
  // The render is far longer than any test: the shell waits for its first progress line (an event, with a
  // generous cap), then sends SIGINT as Ctrl-C would.
  const std::string script = "'" + std::string(WB_WORKBENCH_BIN) +
                             "' render --size 48x32 --spp 1000000 --out '" + out.string() + "' --stats '" +
                             stats.string() + "' > '" + log.string() +
                             "' 2>&1 & pid=$!; "
                             "for i in $(seq 6000); do grep -q 'ETA' '" +
                             log.string() +
                             "' && break; kill -0 $pid 2>/dev/null || break; sleep 0.1; done; "
                             "kill -INT $pid; wait $pid; echo \"exit=$?\"";
  const fs::path scriptFile = dir / "interrupt.sh";
  std::ofstream(scriptFile) << script << "\n";
  const auto r = wb::testing::runCommand("bash '" + scriptFile.string() + "'");
  std::ifstream lf(log);
  const std::string printed((std::istreambuf_iterator<char>(lf)), {});
  EXPECT_NE(r.output.find("exit=130"), std::string::npos) << r.output << printed;
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
  const fs::path dir = fs::temp_directory_path() / ("wb_abort_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path log = dir / "log.txt";
  const std::string script = "'" + std::string(WB_WORKBENCH_BIN) +
                             "' render --size 48x32 --spp 1000000 --out '" + (dir / "never.png").string() +
                             "' > '" + log.string() +
                             "' 2>&1 & pid=$!; "
                             "for i in $(seq 6000); do grep -q 'ETA' '" +
                             log.string() +
                             "' && break; kill -0 $pid 2>/dev/null || break; sleep 0.1; done; "
                             "kill -ABRT $pid; wait $pid; echo \"exit=$?\"";
  const fs::path scriptFile = dir / "abort.sh";
  std::ofstream(scriptFile) << script << "\n";
  const auto r = wb::testing::runCommand("bash '" + scriptFile.string() + "'");
  std::ifstream lf(log);
  const std::string printed((std::istreambuf_iterator<char>(lf)), {});
  EXPECT_NE(r.output.find("exit=134"), std::string::npos) << r.output << printed;
  EXPECT_NE(printed.find("*** workbench: fatal signal 6 (ABRT) in thread "), std::string::npos) << printed;
  EXPECT_NE(printed.find("its call stack:\n"), std::string::npos) << printed;
  fs::remove_all(dir);
}
