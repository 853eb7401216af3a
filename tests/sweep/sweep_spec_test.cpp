// Sweep files, task ids, task states from a sweep folder and the merge's refusal of missing tasks, on files
// the tests write (no rendering: tests/sweep/sweep_cli_test.cpp runs real sweeps).
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/sweep/sweep_merge.h"
#include "app/sweep/sweep_slurm.h"
#include "app/sweep/sweep_spec.h"
#include "app/sweep/sweep_state.h"
#include "common/json_text.h"
#include "eval/image.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace wb::app::sweep;

namespace {

fs::path tempDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("wb_sweep_spec_" + std::to_string(::getpid())) / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// The error message of parseSpec on `text` (empty when it parses).
std::string specError(const std::string& text, const fs::path& base = fs::temp_directory_path()) {
  try {
    parseSpec(text, "spec.json", base);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

const char* kTwoByTwo = R"({
  "name": "t", "size": "8x8", "seeds": 2, "checkpoints": [1, 2],
  "scenes": [{"name": "a"}, {"name": "b", "flags": "--max-bounces 3", "reference_spp": 4}],
  "configs": [{"name": "x"}, {"name": "y", "flags": ["--sampler", "pcg"], "defines": {"K": "1"}, "mode": "pathtrace"}]
})";

}  // namespace

TEST(SweepSpec, ExpandsIntoStableTaskIds) {
  const Sweep s = parseSpec(kTwoByTwo, "spec.json", "/");
  std::vector<std::string> ids;
  for (const auto& t : s.tasks) ids.push_back(t.id);
  const std::vector<std::string> expected = {"a.ref",  "b.ref",  "a.x.s0", "a.x.s1", "a.y.s0",
                                             "a.y.s1", "b.x.s0", "b.x.s1", "b.y.s0", "b.y.s1"};
  EXPECT_EQ(ids, expected);
  EXPECT_EQ(s.scenes[0].referenceSpp, 1024u);  // the default
  EXPECT_EQ(s.scenes[1].referenceSpp, 4u);
  // A configuration's flags over the scene's over the sweep's; defines and mode become flags.
  const auto ro = s.configOptions(1, 1);
  EXPECT_EQ(ro.params.render.maxBounces, 3u);
  EXPECT_EQ(ro.params.render.width, 8u);
  ASSERT_EQ(ro.params.render.defines.size(), 1u);
  EXPECT_EQ(ro.params.render.defines[0].first, "K");
  // Seeds depend on the task only: seed index and the configuration's --seed.
  EXPECT_EQ(s.taskSeed(s.tasks[2]), s.taskSeed(s.tasks[6]));
  EXPECT_NE(s.taskSeed(s.tasks[2]), s.taskSeed(s.tasks[3]));
  // Found by id or number.
  EXPECT_EQ(s.findTask("b.y.s1"), 9u);
  EXPECT_EQ(s.findTask("3"), 3u);
  EXPECT_THROW(s.findTask("c.x.s0"), std::invalid_argument);
  EXPECT_THROW(s.findTask("10"), std::invalid_argument);
}

TEST(SweepSpec, ItsExpandedFormReadsBackTheSame) {
  const Sweep s = parseSpec(kTwoByTwo, "spec.json", "/");
  const Sweep again = parseSpec(wb::jsonText(toJson(s)), "sweep.json", "/");
  ASSERT_EQ(again.tasks.size(), s.tasks.size());
  for (size_t i = 0; i < s.tasks.size(); ++i) {
    EXPECT_EQ(again.tasks[i].id, s.tasks[i].id);
    EXPECT_EQ(again.taskSeed(again.tasks[i]), s.taskSeed(s.tasks[i]));
  }
  EXPECT_EQ(again.configs[1].flags, s.configs[1].flags);
  EXPECT_EQ(again.checkpoints, s.checkpoints);
}

TEST(SweepSpec, BadFilesNameTheLineOrTheEntry) {
  // JSON syntax: the line.
  EXPECT_NE(specError("{\n \"name\": \"t\",\n \"size\": 8x8\n}").find("spec.json: line 3"), std::string::npos)
      << specError("{\n \"name\": \"t\",\n \"size\": 8x8\n}");
  const std::string base = R"("size": "8x8", "checkpoints": [1], "scenes": [{"name": "a"}])";
  auto with = [&](const std::string& more) {
    return specError("{" + base + (more.empty() ? "" : ", ") + more + "}");
  };
  EXPECT_EQ(with(""), "");
  EXPECT_NE(with(R"("seed": 3)").find("unknown key 'seed'"), std::string::npos) << with(R"("seed": 3)");
  EXPECT_NE(with(R"("seeds": 0)").find("seeds"), std::string::npos);
  EXPECT_NE(
      specError(R"({"size": "8x8", "checkpoints": [4, 2], "scenes": [{"name": "a"}]})").find("must increase"),
      std::string::npos);
  EXPECT_NE(specError(R"({"checkpoints": [1], "scenes": [{"name": "a"}]})").find("size"), std::string::npos);
  const std::string badFlag = with(R"("configs": [{"name": "ok"}, {"name": "bad", "flags": "--bogus 1"}])");
  EXPECT_NE(badFlag.find("configs[1] (bad)"), std::string::npos) << badFlag;
  EXPECT_NE(badFlag.find("--bogus"), std::string::npos) << badFlag;
  const std::string badValue = with(R"("configs": [{"name": "s", "flags": "--sampler nope"}])");
  EXPECT_NE(badValue.find("configs[0] (s)"), std::string::npos) << badValue;
  EXPECT_NE(
      with(R"("configs": [{"name": "s", "flags": "--size 4x4"}])").find("cannot change the scene or --size"),
      std::string::npos);
  EXPECT_NE(with(R"("configs": [{"name": "a b"}])").find("configs[0].name"), std::string::npos);
  EXPECT_NE(with(R"("configs": [{"name": "x"}, {"name": "x"}])").find("names two configurations"),
            std::string::npos);
  const std::string missing = specError(
      R"({"size": "8x8", "checkpoints": [1], "scenes": [{"name": "a", "path": "no/such.gltf"}]})", "/tmp");
  EXPECT_NE(missing.find("scenes[0].path"), std::string::npos) << missing;
  EXPECT_NE(missing.find("/tmp/no/such.gltf"), std::string::npos)
      << missing;  // relative to the file's folder
  EXPECT_NE(with(R"("configs": [{"name": "q", "flags": "--env 'unclosed"}])").find("unbalanced quote"),
            std::string::npos);
}

namespace {

// A sweep of one scene with a reference file, three configurations of two seeds, at 4x4 with checkpoints 1
// and 2, and the result files its tasks would write (errors made up; images constant per task).
struct FakeSweep {
  fs::path dir;
  Sweep sweep;

  explicit FakeSweep(const std::string& name) : dir(tempDir(name)) {
    wb::eval::ImageRGBA ref;
    ref.width = ref.height = 4;
    ref.pixels.assign(4 * 4 * 4, 0.5f);
    wb::eval::writeExr(dir / "ref.exr", ref);
    const std::string text = R"({"name": "fake", "size": "4x4", "seeds": 2, "checkpoints": [1, 2],
      "scenes": [{"name": "a", "reference": "ref.exr"}],
      "configs": [{"name": "x"}, {"name": "y", "flags": "--sampler pcg"}, {"name": "z", "flags": "--no-mis"}]})";
    sweep = parseSpec(text, "spec.json", dir);
    json ids = json::array();
    for (const auto& t : sweep.tasks) ids.push_back(t.id);
    std::ofstream(dir / "sweep.json") << wb::jsonText(json{{"sweep", toJson(sweep)}, {"tasks", ids}});
  }

  void finish(size_t task, float value) {
    const Task& t = sweep.tasks[task];
    fs::create_directories(taskDir(dir, t));
    json cps = json::array();
    for (uint32_t spp : sweep.checkpoints) {
      wb::eval::ImageRGBA img;
      img.width = img.height = 4;
      img.pixels.assign(4 * 4 * 4, value / float(spp));
      wb::eval::writeExr(checkpointImage(dir, t, spp), img);
      const double e = (value / spp - 0.5) * (value / spp - 0.5);
      cps.push_back(json{{"spp", spp},
                         {"seconds", 0.1 * spp},
                         {"mse", e},
                         {"rel_mse", e / 0.26},
                         {"mean_rgb", {value / spp, value / spp, value / spp}}});
    }
    std::ofstream(resultFile(dir, t)) << wb::jsonText(json{{"checkpoints", cps},
                                                           {"device", "fake"},
                                                           {"host", "h"},
                                                           {"fireflies", json::object()},
                                                           {"startup", json::object()}});
  }
};

}  // namespace

TEST(SweepMerge, RefusesMissingTasksUnlessPartialAndThenNamesThem) {
  FakeSweep f("merge");
  for (size_t i = 0; i < f.sweep.tasks.size(); ++i)
    if (f.sweep.tasks[i].id != "a.y.s1") f.finish(i, 1.0f + 0.1f * float(i));
  const MergeResult refused = mergeSweep(f.dir, f.sweep, false);
  EXPECT_FALSE(refused.written);
  EXPECT_EQ(refused.missing, std::vector<std::string>{"a.y.s1"});
  EXPECT_NE(refused.message.find("a.y.s1"), std::string::npos) << refused.message;
  EXPECT_NE(refused.message.find("--partial"), std::string::npos) << refused.message;
  EXPECT_FALSE(fs::exists(f.dir / "report"));

  const MergeResult partial = mergeSweep(f.dir, f.sweep, true);
  ASSERT_TRUE(partial.written);
  std::ifstream md(f.dir / "report" / "summary.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Partial report: missing a.y.s1"), std::string::npos) << text;
  std::ifstream scene(f.dir / "report" / "a" / "converge.md");
  const std::string sceneText((std::istreambuf_iterator<char>(scene)), std::istreambuf_iterator<char>());
  EXPECT_NE(sceneText.find("y lacks a.y.s1"), std::string::npos) << sceneText;
  // The configuration with one seed left is still reported, from that seed.
  std::ifstream csv(f.dir / "report" / "a" / "converge.csv");
  std::string line;
  int yRows = 0;
  while (std::getline(csv, line)) yRows += line.rfind("y,", 0) == 0;
  EXPECT_EQ(yRows, 2);

  f.finish(f.sweep.findTask("a.y.s1"), 2.0f);
  const MergeResult full = mergeSweep(f.dir, f.sweep, false);
  EXPECT_TRUE(full.written);
  EXPECT_TRUE(full.missing.empty());
  const json summary = json::parse(std::ifstream(f.dir / "report" / "summary.json"));
  EXPECT_FALSE(summary["partial"].get<bool>());
  // Seeds combined: means and spreads over the two seeds of each configuration.
  const json& x = summary["scenes"][0]["configs"][0];
  EXPECT_EQ(x["name"], "x");
  EXPECT_EQ(x["seeds"], 2);
  EXPECT_GT(x["rel_mse"]["sd"].get<double>(), 0.0);
}

TEST(SweepState, TasksAreDoneFailedWithTheirLogOrNeverStarted) {
  FakeSweep f("state");
  f.finish(0, 1.0f);
  const Task& started = f.sweep.tasks[1];
  fs::create_directories(taskDir(f.dir, started));
  std::ofstream(attemptFile(f.dir, started)) << R"({"host": "node7", "pid": 1})";
  std::ofstream(logFile(f.dir, started))
      << "line 1\nprogress\r50%\r100%\nworkbench sweep run-task: error: boom\n";
  const auto states = taskStates(f.dir, f.sweep, QueueView{}, 2);
  EXPECT_EQ(states[0].state, State::Done);
  EXPECT_EQ(states[1].state, State::Failed);
  EXPECT_NE(states[1].detail.find("node7"), std::string::npos) << states[1].detail;
  EXPECT_EQ(states[1].logTail, (std::vector<std::string>{"100%", "workbench sweep run-task: error: boom"}));
  EXPECT_EQ(states[2].state, State::Failed);
  EXPECT_NE(states[2].detail.find("never started"), std::string::npos);

  // What Slurm's queue says wins for a task that has not ended: queued, or never able to start.
  QueueView q;
  q.queried = true;
  q.tasks[2] = QueuedJob{"12_2", "PENDING", "Dependency"};
  q.tasks[3] = QueuedJob{"12_3", "PENDING", "DependencyNeverSatisfied"};
  q.tasks[4] = QueuedJob{"12_4", "RUNNING", "None"};
  const auto queued = taskStates(f.dir, f.sweep, q, 2);
  EXPECT_EQ(queued[2].state, State::Pending);
  EXPECT_EQ(queued[3].state, State::Failed);
  EXPECT_NE(queued[3].detail.find("can never start"), std::string::npos);
  EXPECT_EQ(queued[4].state, State::Running);

  // When squeue cannot answer, a task that never started is not called failed: Slurm may still hold it.
  QueueView unknown;
  unknown.queried = true;
  unknown.error = "squeue failed (exit 1): cannot connect";
  const auto guessed = taskStates(f.dir, f.sweep, unknown, 2);
  EXPECT_EQ(guessed[2].state, State::Pending);
  EXPECT_NE(guessed[2].detail.find("not known"), std::string::npos);
  EXPECT_EQ(guessed[1].state, State::Failed) << "it started and ended without a result";

  // A task holding its lock runs.
  const FileLock lock(taskDir(f.dir, started) / "lock");
  ASSERT_TRUE(lock.held());
  EXPECT_EQ(taskStates(f.dir, f.sweep, QueueView{}, 2)[1].state, State::Running);
}

TEST(SweepState, LoadingAFolderWithoutASweepSaysSo) {
  const fs::path d = tempDir("empty");
  try {
    loadSweep(d);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("holds no sweep"), std::string::npos) << e.what();
  }
}

TEST(SweepScripts, WordsAreQuotedWhenTheyNeedIt) {
  EXPECT_EQ(shellQuote("/a/b-c_d.txt"), "/a/b-c_d.txt");
  EXPECT_EQ(shellQuote("a b"), "'a b'");
  EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(shellQuote(""), "''");
}
