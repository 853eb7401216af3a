// `workbench sweep` here (--local) as a user runs it: a failing task is listed with its log and keeps the
// merge from reporting; bad command lines and sweep files are one-line errors naming the flag or entry.
#include <gtest/gtest.h>

#include "sweep_test_util.h"

using namespace wb::testing;
using nlohmann::json;

TEST(SweepCli, AFailingTaskIsListedWithItsLogAndKeepsTheMergeFromReporting) {
  const fs::path root = sweepTempDir("failing");
  // "bad" asks for a device this machine does not have: its task fails when it starts.
  std::ofstream(root / "spec.json")
      << R"({"name": "f", "size": "16x16", "checkpoints": [1, 2], "reference_spp": 4,
    "scenes": [{"name": "default"}],
    "configs": [{"name": "ok"}, {"name": "bad", "flags": "--device no-such-device"}]})";
  const fs::path dir = root / "out";
  const CommandResult r = sweep((root / "spec.json").string() + " --local --out " + dir.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("default.bad.s0 FAILED"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no device matches --device 'no-such-device'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 task(s) not done: default.bad.s0"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "report"));

  const json status = sweepStatus(dir);
  ASSERT_EQ(status["tasks"].size(), 3u) << status.dump(1);
  EXPECT_EQ(status["tasks"][0]["state"], "done");  // the reference
  EXPECT_EQ(status["tasks"][1]["state"], "done");
  const json& bad = status["tasks"][2];
  EXPECT_EQ(bad["id"], "default.bad.s0");
  EXPECT_EQ(bad["state"], "failed");
  EXPECT_NE(bad["log_tail"].dump().find("no device matches"), std::string::npos) << bad.dump(1);

  const CommandResult merge = sweep("merge " + dir.string());
  EXPECT_EQ(merge.code, 1) << merge.output;
  EXPECT_NE(merge.output.find("1 of 3 task(s) are not done: default.bad.s0"), std::string::npos)
      << merge.output;
  // Resume runs only the failed task (it fails again: the device is still missing).
  const std::string doneResult = fileText(dir / "tasks" / "default.ok.s0" / "result.json");
  const CommandResult resumed = sweep("resume " + dir.string());
  EXPECT_EQ(resumed.code, 1) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming 1 of 3 task(s)"), std::string::npos) << resumed.output;
  EXPECT_EQ(fileText(dir / "tasks" / "default.ok.s0" / "result.json"), doneResult) << "a done task ran again";
}

TEST(SweepCli, BadCommandLinesAreOneLineErrors) {
  const fs::path root = sweepTempDir("bad");
  std::ofstream(root / "spec.json") << R"({"size": "8x8", "checkpoints": [1], "scenes": [{"name": "a"}]})";
  const std::string spec = (root / "spec.json").string() + " ";
  const std::string out = " --out " + (root / "out").string();
  struct Case {
    std::string args, says;
  };
  for (const Case& c : std::vector<Case>{
           {spec + out, "--local or --slurm"},
           {spec + "--local --slurm" + out, "not both"},
           {spec + "--slurm -j 2" + out, "-j/--jobs goes with --local"},
           {spec + "--local --partition gpu" + out, "--partition goes with --slurm"},
           {spec + "--slurm --sbatch-arg=--array=1-2" + out, "--array is set by the sweep itself"},
           {spec + "--local", "--out"},
           {"--local" + out, "expected a sweep file"},
       }) {
    const CommandResult r = sweep(c.args);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find("workbench sweep: error:"), std::string::npos) << c.args << ": " << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << ": " << r.output;
  }
  std::ofstream(root / "broken.json") << "{\n  \"size\": \"8x8\",\n  \"checkpoints\": [1,]\n}";
  const CommandResult broken = sweep((root / "broken.json").string() + " --local" + out);
  EXPECT_EQ(broken.code, 2) << broken.output;
  EXPECT_NE(broken.output.find("broken.json: line 3"), std::string::npos) << broken.output;

  const CommandResult none = sweep("status " + root.string());
  EXPECT_EQ(none.code, 1) << none.output;
  EXPECT_NE(none.output.find("holds no sweep"), std::string::npos) << none.output;
}

TEST(SweepCli, AFolderHoldingASweepIsNotOverwritten) {
  const fs::path root = sweepTempDir("again");
  std::ofstream(root / "spec.json") << R"({"size": "8x8", "checkpoints": [1], "reference_spp": 2,
    "scenes": [{"name": "a"}]})";
  const std::string args = (root / "spec.json").string() + " --local --out " + (root / "out").string();
  const CommandResult first = sweep(args);
  ASSERT_EQ(first.code, 0) << first.output;
  const CommandResult second = sweep(args);
  EXPECT_EQ(second.code, 2) << second.output;
  EXPECT_NE(second.output.find("holds a sweep already"), std::string::npos) << second.output;
  // Resume of a complete sweep runs nothing and merges again.
  const CommandResult resumed = sweep("resume " + (root / "out").string());
  EXPECT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming 0 of 2 task(s)"), std::string::npos) << resumed.output;
}
