#include "app/sweep/sweep_merge.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <optional>

#include "app/converge_report.h"
#include "app/converge_run.h"
#include "app/sweep/sweep_state.h"
#include "common/env.h"
#include "common/json_text.h"
#include "eval/metrics.h"

using nlohmann::json;

namespace wb::app::sweep {
namespace {

struct Spread {
  double mean = 0, sd = 0, min = 0, max = 0, median = 0;
  size_t n = 0;
};

Spread spread(std::vector<double> v) {
  Spread s;
  s.n = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.min = v.front();
  s.max = v.back();
  s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  s.mean = app::mean(v);
  double q = 0;
  for (double x : v) q += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(q / double(v.size() - 1)) : 0.0;
  return s;
}

json spreadJson(const Spread& s) {
  return json{{"n", s.n},     {"mean", s.mean},     {"sd", s.sd},
              {"min", s.min}, {"median", s.median}, {"max", s.max}};
}

std::string joined(const std::vector<std::string>& v, const std::string& sep, size_t limit = SIZE_MAX) {
  std::string out;
  for (size_t i = 0; i < v.size() && i < limit; ++i) out += (i ? sep : "") + v[i];
  if (v.size() > limit) out += sep + "... (" + std::to_string(v.size() - limit) + " more)";
  return out;
}

double num(const json& j, const char* key) {
  return j.contains(key) && j[key].is_number() ? j[key].get<double>() : 0.0;
}

// A run's result holds a measurement at each of the sweep's checkpoints; throws std::runtime_error naming the
// file otherwise (a result of another sweep or version: it must be made again).
void checkRunResult(const json& r, const Sweep& s, const fs::path& file) {
  const json cps = r.value("checkpoints", json());
  bool ok = cps.is_array() && cps.size() == s.checkpoints.size();
  for (size_t i = 0; ok && i < cps.size(); ++i) {
    const json& c = cps[i];
    ok = c.is_object() && c.value("spp", 0u) == s.checkpoints[i] && c.contains("mean_rgb") &&
         c["mean_rgb"].is_array() && c["mean_rgb"].size() == 3;
    for (size_t k = 0; ok && k < 3; ++k) ok = c["mean_rgb"][k].is_number();
  }
  if (!ok) {
    throw std::runtime_error(
        file.string() +
        " does not hold a measurement at each of this sweep's checkpoints: remove it and run "
        "the task again (`workbench sweep resume DIR`)");
  }
}

// One configuration on one scene: its seeds' results combined as converge combines the runs of a
// configuration (errors per checkpoint over the runs, the variance between runs, the first run's final
// image).
ConfigResult combineSeeds(const fs::path& dir, const Sweep& s, const std::string& name,
                          const std::vector<std::pair<const Task*, const json*>>& seeds,
                          const std::vector<std::string>& flags) {
  ConfigResult r;
  r.name = name;
  r.flags = joined(flags, " ");
  for (size_t ci = 0; ci < s.checkpoints.size(); ++ci) {
    Checkpoint cp;
    cp.spp = s.checkpoints[ci];
    std::vector<eval::ImageRGBA> images;
    for (const auto& [task, result] : seeds) {
      const json& c = (*result)["checkpoints"].at(ci);
      cp.seconds.push_back(num(c, "seconds"));
      cp.mse.push_back(num(c, "mse"));
      cp.relMse.push_back(num(c, "rel_mse"));
      const json& m = c["mean_rgb"];
      cp.mean.push_back({m.at(0).get<double>(), m.at(1).get<double>(), m.at(2).get<double>()});
      if (seeds.size() >= 2 || ci + 1 == s.checkpoints.size())
        images.push_back(eval::readExr(checkpointImage(dir, *task, cp.spp)));
    }
    if (images.size() >= 2) cp.variance = eval::runStats(images).meanVariance();
    if (ci + 1 == s.checkpoints.size()) cp.images.push_back(std::move(images.front()));
    r.checkpoints.push_back(std::move(cp));
  }
  std::vector<double> setup;
  for (const auto& [task, result] : seeds) {
    r.dropped += (*result).value("nan_inf_dropped", uint64_t{0});
    setup.push_back(num(result->value("startup", json::object()), "session_setup_seconds"));
  }
  const json ff = seeds.front().second->value("fireflies", json::object());
  r.fireflies.maxOverMean = num(ff, "max_over_mean");
  r.fireflies.fractionAbove10x = num(ff, "fraction_above_10x");
  r.fireflies.meanLuminance = num(ff, "mean_luminance");
  r.fireflies.maxLuminance = num(ff, "max_luminance");
  r.setupSeconds = app::mean(setup);
  return r;
}

std::string checkpointList(const Sweep& s) {
  std::string out;
  for (size_t i = 0; i < s.checkpoints.size(); ++i) out += (i ? ", " : "") + std::to_string(s.checkpoints[i]);
  return "checkpoints at " + out + " spp";
}

void writeStartup(std::ostream& md, json& summary, const std::vector<std::optional<json>>& results,
                  const Sweep& s) {
  std::vector<double> load, setup, toSession, first, wall;
  uint64_t hits = 0, misses = 0, compiles = 0;
  std::vector<std::pair<double, std::string>> slowest;
  for (size_t i = 0; i < s.tasks.size(); ++i) {
    if (!results[i] || s.tasks[i].kind != TaskKind::Run) continue;
    const json st = results[i]->value("startup", json::object());
    load.push_back(num(st, "scene_load_seconds"));
    setup.push_back(num(st, "session_setup_seconds"));
    toSession.push_back(num(st, "to_session_seconds"));
    first.push_back(num(st, "first_sample_seconds"));
    wall.push_back(num(*results[i], "wall_seconds"));
    if (st.contains("shader_cache")) {
      hits += st["shader_cache"].value("hits", uint64_t{0});
      misses += st["shader_cache"].value("misses", uint64_t{0});
      compiles += st["shader_cache"].value("compiles", uint64_t{0});
    }
    slowest.emplace_back(toSession.back() + first.back(), s.tasks[i].id);
  }
  const Spread l = spread(load), se = spread(setup), ts = spread(toSession), f = spread(first),
               w = spread(wall);
  summary["startup"] = {{"scene_load_seconds", spreadJson(l)},
                        {"session_setup_seconds", spreadJson(se)},
                        {"to_session_seconds", spreadJson(ts)},
                        {"first_sample_seconds", spreadJson(f)},
                        {"wall_seconds", spreadJson(w)},
                        {"shader_cache", {{"hits", hits}, {"misses", misses}, {"compiles", compiles}}}};
  md << "\n## Task start-up (" << l.n << " run tasks)\n\n";
  md << "Each task is a process of its own: it loads its scene, makes its device and session (shaders from "
        "the SPIR-V cache, acceleration structures), then renders; its first sample holds the pipelines' "
        "compile on drivers that compile at the first dispatch (lavapipe: from Mesa's cache when warm).\n\n";
  md << "| seconds | mean | median | max |\n|---|---|---|---|\n";
  auto row = [&](const char* what, const Spread& x) {
    md << "| " << what << " | " << fmt("%.3f", x.mean) << " | " << fmt("%.3f", x.median) << " | "
       << fmt("%.3f", x.max) << " |\n";
  };
  row("scene load", l);
  row("session set-up (device, shaders, acceleration structures)", se);
  row("process start to session ready", ts);
  row("first sample", f);
  row("whole task", w);
  md << "\nShader cache over all run tasks: " << hits << " hits, " << misses << " misses (" << compiles
     << " glslang compiles)" << (misses == 0 ? ": every task found its shaders in the cache" : "") << ".\n";
  std::sort(slowest.rbegin(), slowest.rend());
  if (!slowest.empty()) {
    md << "Slowest starts (to session + first sample):";
    for (size_t i = 0; i < slowest.size() && i < 5; ++i)
      md << (i ? "," : "") << " `" << slowest[i].second << "` " << fmt("%.2f", slowest[i].first) << " s";
    md << ".\n";
  }
}

void writeTasksCsv(const fs::path& path, const std::vector<std::optional<json>>& results, const Sweep& s) {
  std::ofstream f(path);
  f << "number,task,kind,scene,config,seed_index,state,host,slurm_job,device,scene_load_seconds,"
       "session_setup_seconds,to_session_seconds,first_sample_seconds,render_seconds,wall_seconds,"
       "shader_cache_misses,final_rel_mse\n";
  for (size_t i = 0; i < s.tasks.size(); ++i) {
    const Task& t = s.tasks[i];
    f << i << "," << t.id << "," << (t.kind == TaskKind::Reference ? "reference" : "run") << ","
      << s.scenes[t.scene].name << "," << (t.kind == TaskKind::Run ? s.configs[t.config].name : "") << ","
      << (t.kind == TaskKind::Run ? std::to_string(t.seedIndex) : "") << ",";
    if (!results[i]) {
      f << "missing,,,,,,,,,,,\n";
      continue;
    }
    const json& r = *results[i];
    const json st = r.value("startup", json::object());
    const json cps = r.value("checkpoints", json::array());
    f << "done," << r.value("host", "") << "," << r.value("slurm_job", "") << "," << r.value("device", "")
      << "," << fmt("%.4f", num(st, "scene_load_seconds")) << ","
      << fmt("%.4f", num(st, "session_setup_seconds")) << "," << fmt("%.4f", num(st, "to_session_seconds"))
      << "," << fmt("%.4f", num(st, "first_sample_seconds")) << "," << fmt("%.4f", num(r, "render_seconds"))
      << "," << fmt("%.4f", num(r, "wall_seconds")) << ","
      << (st.contains("shader_cache") ? std::to_string(st["shader_cache"].value("misses", 0)) : "") << ","
      << (cps.empty() ? "" : fmt("%.6g", num(cps.back(), "rel_mse"))) << "\n";
  }
}

}  // namespace

MergeResult mergeSweep(const fs::path& dir, const Sweep& s, bool partial) {
  const auto t0 = std::chrono::steady_clock::now();
  MergeResult out;
  std::vector<std::optional<json>> results(s.tasks.size());
  for (size_t i = 0; i < s.tasks.size(); ++i) {
    results[i] = readResult(dir, s.tasks[i]);
    if (!results[i]) {
      out.missing.push_back(s.tasks[i].id);
    } else if (s.tasks[i].kind == TaskKind::Run) {
      checkRunResult(*results[i], s, resultFile(dir, s.tasks[i]));
    }
  }
  if (!out.missing.empty() && !partial) {
    out.message = std::to_string(out.missing.size()) + " of " + std::to_string(s.tasks.size()) +
                  " task(s) are not done: " + joined(out.missing, ", ", 20) +
                  " (`workbench sweep status DIR` says why; `sweep resume DIR` runs them; `--partial` "
                  "reports without them)";
    return out;
  }
  const fs::path report = dir / "report";
  std::error_code ec;
  fs::remove_all(report, ec);
  fs::create_directories(report);

  json summary{{"sweep", s.name},         {"spec", s.specFile},
               {"tasks", s.tasks.size()}, {"done", s.tasks.size() - out.missing.size()},
               {"missing", out.missing},  {"partial", !out.missing.empty()},
               {"scenes", json::array()}};
  std::map<std::string, size_t> hosts, devices;
  for (const auto& r : results) {
    if (!r) continue;
    ++hosts[r->value("host", "?")];
    ++devices[r->value("device", "?")];
  }
  std::string deviceText;
  for (const auto& [d, n] : devices) deviceText += (deviceText.empty() ? "" : ", ") + d;

  std::ofstream md(report / "summary.md");
  md << "# Sweep: " << s.name << "\n\n";
  md << "- Sweep file `" << s.specFile << "`: " << s.scenes.size() << " scene(s) x " << s.configs.size()
     << " configuration(s) x " << s.seeds << " seed(s) at " << s.size << ", " << checkpointList(s) << "; "
     << s.tasks.size() << " tasks (" << s.referenceCount() << " reference renders).\n";
  md << "- Done: " << (s.tasks.size() - out.missing.size()) << " of " << s.tasks.size() << ".";
  if (!out.missing.empty()) md << " **Partial report: missing " << joined(out.missing, ", ") << ".**";
  md << "\n- Devices: " << deviceText << ". Hosts:";
  for (const auto& [h, n] : hosts) md << " " << h << " (" << n << " tasks)";
  md << ".\n";
  md << "\n## Final checkpoint per scene and configuration (spread over seeds)\n\n";
  md << "| scene | config | spp | seeds | relMSE mean | relMSE sd | relMSE min | relMSE max | RMSE mean | "
        "time (s) mean | efficiency | report |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";

  for (size_t si = 0; si < s.scenes.size(); ++si) {
    const SceneSpec& sc = s.scenes[si];
    json sj{{"name", sc.name}, {"configs", json::array()}};
    const long refTask = s.referenceTask(si);
    if (refTask >= 0 && !results[size_t(refTask)]) {
      sj["skipped"] = "its reference task " + sc.name + ".ref is not done";
      summary["scenes"].push_back(sj);
      md << "| " << sc.name << " | (no reference: task `" << sc.name
         << ".ref` missing) | | | | | | | | | | |\n";
      continue;
    }
    const RenderOptions base = s.sceneOptions(si);
    std::string refDescription;
    const eval::ImageRGBA reference =
        loadReferenceFile(referenceImage(dir, s, si).string(), base.params.render.width,
                          base.params.render.height, refDescription);
    if (refTask >= 0) {
      refDescription = "rendered by task `" + sc.name + ".ref`: " + std::to_string(sc.referenceSpp) +
                       " spp of the path tracer with the sweep's and the scene's flags and its own seed "
                       "(`tasks/" +
                       sc.name + ".ref/reference.exr`)";
    }
    std::vector<ConfigResult> configs;
    std::vector<std::string> notes;
    uint32_t runs = 0;
    for (size_t k = 0; k < s.configs.size(); ++k) {
      std::vector<std::pair<const Task*, const json*>> seeds;
      std::vector<std::string> missing;
      for (size_t i = 0; i < s.tasks.size(); ++i) {
        const Task& t = s.tasks[i];
        if (t.kind != TaskKind::Run || t.scene != si || t.config != k) continue;
        if (results[i]) {
          seeds.emplace_back(&t, &*results[i]);
        } else {
          missing.push_back(t.id);
        }
      }
      if (!missing.empty())
        notes.push_back("**Partial:** " + s.configs[k].name + " lacks " + joined(missing, ", "));
      if (seeds.empty()) continue;
      runs = std::max(runs, uint32_t(seeds.size()));
      configs.push_back(combineSeeds(dir, s, s.configs[k].name, seeds, s.configs[k].flags));
      // The spread of the final errors over the seeds (the report's table has their means).
      std::vector<double> rel, rmse, secs;
      for (const auto& [task, result] : seeds) {
        const json& c = (*result)["checkpoints"].back();
        rel.push_back(num(c, "rel_mse"));
        rmse.push_back(std::sqrt(num(c, "mse")));
        secs.push_back(num(c, "seconds"));
      }
      const Spread r = spread(rel), e = spread(rmse), t = spread(secs);
      const Checkpoint& last = configs.back().checkpoints.back();
      const double m = app::mean(last.mse), tm = app::mean(last.seconds);
      md << "| " << sc.name << " | " << s.configs[k].name << " | " << last.spp << " | " << seeds.size()
         << " | " << fmt("%.4g", r.mean) << " | " << fmt("%.3g", r.sd) << " | " << fmt("%.4g", r.min) << " | "
         << fmt("%.4g", r.max) << " | " << fmt("%.4g", e.mean) << " | " << fmt("%.3f", t.mean) << " | "
         << fmt("%.4g", m > 0 && tm > 0 ? 1.0 / (m * tm) : 0.0) << " | [" << sc.name << "](" << sc.name
         << "/converge.md) |\n";
      sj["configs"].push_back(json{{"name", s.configs[k].name},
                                   {"seeds", seeds.size()},
                                   {"missing", missing},
                                   {"spp", last.spp},
                                   {"rel_mse", spreadJson(r)},
                                   {"rmse", spreadJson(e)},
                                   {"seconds", spreadJson(t)},
                                   {"variance", last.variance}});
    }
    const fs::path sceneDir = report / sc.name;
    fs::create_directories(sceneDir);
    const eval::Rgb refMean = eval::meanRgb(reference);
    writeCsv(sceneDir / "converge.csv", configs, refMean);
    ReportSetup setup;
    setup.scene = sc.path.empty() ? "the default scene" : sc.path;
    setup.width = base.params.render.width;
    setup.height = base.params.render.height;
    setup.budget = checkpointList(s);
    setup.runs = runs;
    setup.device = deviceText;
    setup.reference = refDescription;
    setup.referenceMean = refMean;
    setup.targetRelMse = s.targetRelMse;
    setup.plotNote = writePlot(sceneDir, configs, sc.name);
    setup.notes = notes;
    setup.notes.push_back("Sweep `" + s.name + "`: each run is a task of its own (`" + sc.name +
                          ".CONFIG.sK`), seeds combined here; the spread over seeds is in `../summary.md`.");
    writeSummary(sceneDir, configs, setup, reference);
    sj["report"] = sc.name + "/converge.md";
    summary["scenes"].push_back(sj);
  }
  writeStartup(md, summary, results, s);
  writeTasksCsv(report / "tasks.csv", results, s);
  md << "\n## Files\n\n- Per scene: `SCENE/converge.md` (efficiency table, time to error, error images), "
        "`SCENE/converge.csv`, `SCENE/converge.png`.\n- `tasks.csv`: every task, where it ran and its "
        "start-up; `summary.json`: this summary as data.\n";
  if (const auto job = env::get("SLURM_JOB_ID")) summary["merge_job"] = *job;
  summary["merge_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  md << "- Merged in " << fmt("%.2f", summary["merge_seconds"].get<double>()) << " s.\n";
  md.close();
  writeFileAtomically(report / "summary.json", jsonText(summary, 1) + "\n");
  out.written = true;
  return out;
}

int runMerge(const fs::path& dir, bool partial) {
  try {
    const Sweep s = loadSweep(dir);
    const MergeResult r = mergeSweep(dir, s, partial);
    if (!r.written) {
      std::fprintf(stderr, "workbench sweep merge: error: %s\n", r.message.c_str());
      return 1;
    }
    if (!r.missing.empty()) {
      std::fprintf(stderr, "workbench sweep merge: partial report without %zu task(s): %s\n",
                   r.missing.size(), joined(r.missing, ", ").c_str());
    }
    std::printf("sweep merge: %zu task(s) -> %s (summary.md; per scene converge.md, converge.csv)\n",
                s.tasks.size() - r.missing.size(), (dir / "report").c_str());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "workbench sweep merge: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace wb::app::sweep
