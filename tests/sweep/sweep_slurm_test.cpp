// A sweep on a real Slurm cluster (the single node of scripts/slurm-local.sh, which ctest starts as the
// fixture slurm_local) against the same sweep run here with --local: bit-identical images per task and the
// same report except timings, after run tasks are cancelled, reported by `sweep status`, refused by `sweep
// merge` and submitted again by `sweep resume`. Without a cluster this test fails: it never skips.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>

#include "sweep_test_util.h"

using namespace wb::testing;
using nlohmann::json;

namespace {

fs::path sharedDir() {
  const char* env = std::getenv("WB_SHARED_DIR");
  return env && *env ? fs::path(env) : fs::path(WB_SOURCE_DIR) / ".." / "shared";
}

// 2 scenes (one with a reference task, one with a reference file) x 3 configurations (two samplers and a
// hybrid mode) x 2 seeds at 32x32: 12 runs and one reference render.
fs::path writeSpec(const fs::path& dir) {
  const fs::path shared = sharedDir() / "reference";
  const json spec{{"name", "ci"},
                  {"size", "32x32"},
                  {"flags", "--max-bounces 4"},
                  {"seeds", 2},
                  {"checkpoints", {1, 2, 4}},
                  {"reference_spp", 16},
                  {"scenes",
                   {{{"name", "default"}},
                    {{"name", "cornell"},
                     {"path", (shared / "cornell.gltf").string()},
                     {"flags", "--env-color 0,0,0"},
                     {"reference", (shared / "cornell_cycles.exr").string()}}}},
                  {"configs",
                   {{{"name", "sobol"}, {"flags", "--sampler sobol"}},
                    {{"name", "pcg"}, {"flags", "--sampler pcg"}},
                    {{"name", "hybrid"}, {"mode", "hybrid"}}}}};
  const fs::path p = dir / "ci.json";
  std::ofstream(p) << spec.dump(1);
  return p;
}

size_t countState(const json& status, const std::string& state) {
  return status.value("counts", json::object()).value(state, size_t{0});
}

// The sweep's summary without what depends on timing.
json timeless(json summary) {
  json out = json::array();
  for (auto& scene : summary["scenes"]) {
    for (auto& c : scene["configs"]) c.erase("seconds");
    out.push_back(scene);
  }
  return out;
}

}  // namespace

TEST(SweepSlurm, SameImagesAndReportAsLocalAfterCancelStatusAndResume) {
  const CommandResult sinfo = runCommand("sinfo -h -o %T");
  ASSERT_EQ(sinfo.code, 0)
      << "no Slurm cluster (scripts/slurm-local.sh start; ctest starts it as the fixture "
         "slurm_local): "
      << sinfo.output;
  ASSERT_TRUE(sinfo.output.find("idle") != std::string::npos ||
              sinfo.output.find("mix") != std::string::npos ||
              sinfo.output.find("alloc") != std::string::npos)
      << "the cluster's node is not up: " << sinfo.output;

  const fs::path root = sweepTempDir("slurm");
  const fs::path spec = writeSpec(root);
  const fs::path local = root / "local", slurm = root / "slurm";
  const CommandResult l = sweep(spec.string() + " --local -j 2 --out " + local.string());
  ASSERT_EQ(l.code, 0) << l.output;
  ASSERT_TRUE(fs::exists(local / "report" / "summary.md")) << l.output;

  // Submitted without waiting: the runs wait for the reference render, so two of them are cancelled before
  // they start (or, on a slow cluster, while they run: either way they end without a result). An scontrol
  // that reports a MaxArraySize of 8 makes the sweep split its 12 runs into arrays of 8 and 4, as on a
  // cluster whose limit is below a sweep's size.
  const fs::path bin = root / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "scontrol")
      << "#!/bin/sh\nif [ \"$1 $2\" = \"show config\" ]; then\n"
         "  scontrol_real=$(PATH=${PATH#*:} command -v scontrol)\n"
         "  \"$scontrol_real\" show config | sed 's/^MaxArraySize .*/MaxArraySize = 8/'\n"
         "else PATH=${PATH#*:} exec scontrol \"$@\"; fi\n";
  fs::permissions(bin / "scontrol", fs::perms::owner_all);
  const CommandResult s = runCommand("PATH=" + bin.string() + ":$PATH " + WB_WORKBENCH_BIN + " sweep " +
                                     spec.string() + " --slurm --throttle 2 --out " + slurm.string());
  ASSERT_EQ(s.code, 0) << s.output;
  const json jobs = json::parse(fileText(slurm / "slurm" / "jobs.json"));
  const json& arrays = jobs["submissions"][0]["arrays"];
  ASSERT_EQ(arrays.size(), 3u) << jobs.dump();
  EXPECT_EQ(arrays[0]["kind"], "ref");
  EXPECT_EQ(arrays[1]["kind"], "run");
  EXPECT_EQ(arrays[1]["tasks"].size(), 8u);
  EXPECT_EQ(arrays[2]["kind"], "run");
  EXPECT_EQ(arrays[2]["tasks"].size(), 4u);
  const std::string runs = arrays[1]["job"];
  // Elements 1 and 4 of the runs array: default.sobol.s1 and default.hybrid.s0.
  const CommandResult cancel = runCommand("scancel " + runs + "_1 " + runs + "_4");
  ASSERT_EQ(cancel.code, 0) << cancel.output;
  EXPECT_NE(fileText(slurm / "slurm" / "submit.log").find("%2"), std::string::npos) << "the throttle";
  EXPECT_NE(fileText(slurm / "slurm" / "task.sbatch").find("sweep run-task"), std::string::npos);

  // Once the other tasks are done, the merge job waits on runs that failed: it can never start, and status
  // says so (Slurm re-evaluates dependencies in its own time).
  json status;
  ASSERT_TRUE(waitFor([&] {
    status = sweepStatus(slurm);
    return countState(status, "pending") + countState(status, "running") == 0 &&
           status["merge_jobs"].size() == 1 &&
           status["merge_jobs"][0]["reason"] == "DependencyNeverSatisfied";
  })) << status.dump(1);
  EXPECT_EQ(countState(status, "done"), 11u) << status.dump(1);
  EXPECT_EQ(countState(status, "failed"), 2u) << status.dump(1);
  std::set<std::string> failed;
  for (const auto& t : status["tasks"])
    if (t["state"] == "failed") failed.insert(t["id"].get<std::string>());
  EXPECT_EQ(failed, (std::set<std::string>{"default.sobol.s1", "default.hybrid.s0"})) << status.dump(1);
  const CommandResult text = sweep("status " + slurm.string());
  EXPECT_NE(text.output.find("failed   default.sobol.s1"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("sweep resume"), std::string::npos) << text.output;

  // The merge refuses the incomplete sweep, naming what is missing; --partial reports without it.
  const CommandResult refused = sweep("merge " + slurm.string());
  EXPECT_EQ(refused.code, 1) << refused.output;
  EXPECT_NE(refused.output.find("default.sobol.s1"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("default.hybrid.s0"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(slurm / "report" / "summary.md"));
  const CommandResult partial = sweep("merge --partial " + slurm.string());
  EXPECT_EQ(partial.code, 0) << partial.output;
  EXPECT_NE(fileText(slurm / "report" / "summary.md").find("missing default.sobol.s1, default.hybrid.s0"),
            std::string::npos);

  // Resume submits only those two, and a merge in place of the stuck one.
  const CommandResult resumed = sweep("resume --wait " + slurm.string());
  ASSERT_EQ(resumed.code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming 2 of 13 task(s)"), std::string::npos) << resumed.output;
  status = sweepStatus(slurm);
  EXPECT_EQ(countState(status, "done"), 13u) << status.dump(1);
  EXPECT_TRUE(status["merge_jobs"].empty()) << status.dump(1);
  const json summary = json::parse(fileText(slurm / "report" / "summary.json"));
  EXPECT_FALSE(summary["partial"].get<bool>());
  EXPECT_FALSE(summary.value("merge_job", "").empty()) << "merged by a Slurm job";

  // Bit for bit: every task's images, the error images, the reports' numbers except timings.
  const auto images = filesEndingIn(local / "tasks", ".exr");
  ASSERT_EQ(images.size(), 12u * 3u + 1u);
  EXPECT_EQ(filesEndingIn(slurm / "tasks", ".exr"), images);
  for (const auto& f : images)
    EXPECT_TRUE(fileText(local / "tasks" / f) == fileText(slurm / "tasks" / f)) << f << " differs";
  const auto errorImages = filesEndingIn(local / "report", ".png");
  EXPECT_EQ(filesEndingIn(slurm / "report", ".png"), errorImages);
  for (const auto& f : errorImages) {
    if (fs::path(f).filename() == "converge.png") continue;  // the plot: time on its x axis
    EXPECT_TRUE(fileText(local / "report" / f) == fileText(slurm / "report" / f)) << f << " differs";
  }
  const std::vector<std::string> timings = {"seconds", "seconds_min", "seconds_max", "efficiency"};
  for (const char* scene : {"default", "cornell"}) {
    const fs::path csv = fs::path("report") / scene / "converge.csv";
    EXPECT_EQ(csvWithout(local / csv, timings), csvWithout(slurm / csv, timings)) << scene;
    EXPECT_GT(csvWithout(local / csv, timings).size(), 200u);
  }
  EXPECT_EQ(timeless(json::parse(fileText(local / "report" / "summary.json"))), timeless(summary));
}
