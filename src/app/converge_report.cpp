#include "app/converge_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/file_io.h"
#include "common/paths.h"

namespace fs = std::filesystem;

namespace wb::app {
namespace {

// gnuplot's output, renamed to converge.png once gnuplot succeeded.
constexpr const char* kPlotTemp = ".converge.png.tmp";

void writeErrorImages(const fs::path& dir, const std::vector<ConfigResult>& results,
                      const eval::ImageRGBA& reference, std::ostream& md) {
  double scale = 0;
  md << "\n## Error images (final checkpoint of run 1)\n\n";
  for (const auto& r : results) {
    for (const auto* rows : {&r.checkpoints, &r.denoised}) {
      if (rows->empty() || rows->back().images.empty()) continue;
      const bool denoised = rows == &r.denoised;
      const auto& img = rows->back().images.front();
      const auto rgba = eval::errorHeatmap(img, reference, scale, &scale);  // the first sets the scale
      const std::string file = "error_" + safeName(r.name) + (denoised ? "_denoised" : "") + ".png";
      writeFileAtomically(dir / file, eval::encodePng8(img.width, img.height, rgba), "converge");
      md << "- `" << file << "`: " << r.name << (denoised ? " denoised" : "") << " at " << rows->back().spp
         << " spp\n";
    }
  }
  md << "\n|a - b| averaged over RGB, false colour black - blue - magenta - yellow - white, white = " << scale
     << " (the 99th percentile of the first configuration's error; same scale for all).\n";
}

}  // namespace

double mean(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return v.empty() ? 0.0 : s / double(v.size());
}

std::string safeName(const std::string& name) {
  std::string s;
  for (char c : name) s += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_') ? c : '_';
  return s.empty() ? "config" : s;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string secondsText(double s) {
  return s >= 100.0 ? fmt("%.0f", s) : fmt("%.3g", s);
}

double renderSeconds(const Checkpoint& cp) {
  if (cp.seconds.size() < 2) return mean(cp.seconds);
  return mean(std::vector<double>(cp.seconds.begin() + 1, cp.seconds.end()));
}

std::optional<double> timeToReach(const std::vector<Checkpoint>& checkpoints, double target) {
  for (size_t i = 0; i < checkpoints.size(); ++i) {
    const double e = mean(checkpoints[i].relMse), t = renderSeconds(checkpoints[i]);
    if (e <= target) {
      if (i == 0) return t;
      const double e0 = mean(checkpoints[i - 1].relMse), t0 = renderSeconds(checkpoints[i - 1]);
      if (e0 <= 0 || e <= 0 || t0 <= 0 || e0 == e) return t;
      const double f = std::log(target / e0) / std::log(e / e0);
      return std::exp(std::log(t0) + f * (std::log(t) - std::log(t0)));
    }
  }
  return std::nullopt;
}

void testPixels(ConfigResult& r, const eval::ImageRGBA& reference, uint32_t referenceSpp) {
  for (size_t i = 0; i < r.checkpoints.size(); ++i) {
    Checkpoint& cp = r.checkpoints[i];
    if (cp.images.size() < 2) continue;
    std::optional<eval::ImageRGBA> refVariance;
    if (referenceSpp > 0) {
      // The reference is a render of the same estimator: its variance is one run's, scaled by the samples.
      refVariance = eval::runStats(cp.images).variance;
      const float scale = float(double(cp.spp) / double(referenceSpp));
      for (float& v : refVariance->pixels) v *= scale;
    }
    const eval::ImageRGBA* rv = refVariance ? &*refVariance : nullptr;
    cp.offReference = eval::pixelsOffReference(cp.images, reference, rv);
    if (i < r.denoised.size() && r.denoised[i].images.size() == cp.images.size()) {
      Checkpoint& d = r.denoised[i];
      d.offReference = eval::pixelsOffReference(d.images, reference, rv);
      d.offRaw = eval::pixelsOffPaired(d.images, cp.images);
    }
  }
}

namespace {

// A pixel test's fraction for the CSV (empty when not tested).
std::string fractionField(const eval::PixelTestResult& t) {
  return t.runs ? fmt("%.6g", t.fraction()) : std::string();
}

}  // namespace

eval::Rgb meanOfRuns(const Checkpoint& cp) {
  eval::Rgb mm{0, 0, 0};
  for (const auto& v : cp.mean)
    for (int c = 0; c < 3; ++c) mm[c] += v[c] / double(cp.mean.size());
  return mm;
}

void writeCsv(const fs::path& path, const std::vector<ConfigResult>& results, const eval::Rgb& refMean) {
  std::ostringstream f;
  f << "config,flags,spp,seconds,seconds_min,seconds_max,runs,mse,rmse,relmse,variance,bias2,mean_r,mean_g,"
       "mean_b,ref_mean_r,ref_mean_g,ref_mean_b,efficiency,image,pixels_significant,pixels_significant_vs_"
       "raw,"
       "pixel_test_alpha\n";
  for (const auto& r : results) {
    for (const auto* rows : {&r.checkpoints, &r.denoised}) {
      const bool denoised = rows == &r.denoised;
      for (const auto& cp : *rows) {
        const double t = renderSeconds(cp), m = mean(cp.mse);
        const eval::Rgb mm = meanOfRuns(cp);
        char line[512];
        std::snprintf(
            line, sizeof line,
            "%s,\"%s\",%u,%.6g,%.6g,%.6g,%zu,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%s,",
            r.name.c_str(), r.flags.c_str(), cp.spp, t,
            *std::min_element(cp.seconds.begin(), cp.seconds.end()),
            *std::max_element(cp.seconds.begin(), cp.seconds.end()), cp.seconds.size(), m, std::sqrt(m),
            mean(cp.relMse), cp.variance, std::max(0.0, m - cp.variance), mm[0], mm[1], mm[2], refMean[0],
            refMean[1], refMean[2], (m > 0 && t > 0) ? 1.0 / (m * t) : 0.0, denoised ? "denoised" : "raw");
        f << line << fractionField(cp.offReference) << "," << fractionField(cp.offRaw) << ","
          << (cp.offReference.runs ? fmt("%.6g", cp.offReference.alpha) : std::string()) << "\n";
      }
    }
  }
  writeFileAtomically(path, f.str(), "converge");
}

std::string writePlot(const fs::path& dir, const std::vector<ConfigResult>& results,
                      const std::string& title) {
  const fs::path script = dir / "converge.gp";
  {
    std::ostringstream g;
    g << "set terminal pngcairo size 1100,480 font 'sans,10' noenhanced\n";
    g << "set output '" << (dir / kPlotTemp).string() << "'\n";
    g << "set logscale xy\nset grid\nset key bottom left\nset xlabel 'time (s)'\n";
    // One curve per configuration, and one more for each denoised one.
    std::vector<std::pair<std::string, const std::vector<Checkpoint>*>> curves;
    for (const auto& r : results) {
      curves.push_back({r.denoised.empty() ? r.name : r.name + " raw", &r.checkpoints});
      if (!r.denoised.empty()) curves.push_back({r.name + " denoised", &r.denoised});
    }
    for (size_t i = 0; i < curves.size(); ++i) {
      g << "$d" << i << " << EOD\n";
      for (const auto& cp : *curves[i].second) {
        const double m = mean(cp.mse);
        g << renderSeconds(cp) << " " << mean(cp.relMse) << " " << std::sqrt(m) << "\n";
      }
      g << "EOD\n";
    }
    g << "set multiplot layout 1,2 title '" << title << "'\n";
    for (int panel = 0; panel < 2; ++panel) {
      g << "set ylabel '" << (panel == 0 ? "relMSE" : "RMSE") << "'\nplot ";
      for (size_t i = 0; i < curves.size(); ++i) {
        std::string name = curves[i].first;
        std::replace(name.begin(), name.end(), '_', '-');
        g << (i ? ", " : "") << "$d" << i << " using 1:" << (panel == 0 ? 2 : 3)
          << " with linespoints title '" << name << "'";
      }
      g << "\n";
    }
    g << "unset multiplot\n";
    writeFileAtomically(script, g.str(), "converge");
  }
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    return "gnuplot is not installed (scripts/setup.sh installs gnuplot-nox): no plot; the script is " +
           script.string();
  }
  const std::string cmd = "gnuplot '" + script.string() + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  // gnuplot writes the plot beside its final name; only a whole plot is renamed over converge.png.
  std::error_code ec;
  if (rc != 0) {
    fs::remove(dir / kPlotTemp, ec);
    return "gnuplot failed (exit " + std::to_string(rc) + ") on " + script.string();
  }
  // gnuplot can exit 0 after a write failed: a whole PNG ends with its IEND chunk.
  const auto png = readRegularFile(dir / kPlotTemp);
  if (!png || png->size() < 12 || png->compare(png->size() - 8, 4, "IEND") != 0) {
    fs::remove(dir / kPlotTemp, ec);
    return "gnuplot wrote no whole image (a full disk?) from " + script.string();
  }
  fs::rename(dir / kPlotTemp, dir / "converge.png", ec);
  if (ec) {
    fs::remove(dir / kPlotTemp, ec);
    return "cannot write " + (dir / "converge.png").string() + ": " + ec.message();
  }
  return "";
}

void writeSummary(const fs::path& dir, const std::vector<ConfigResult>& results, const ReportSetup& setup,
                  const eval::ImageRGBA& reference) {
  const eval::Rgb& refMean = setup.referenceMean;
  std::ostringstream md;
  md << "# Convergence: " << setup.scene << "\n\n";
  if (!setup.partialNote.empty()) md << "**Partial:** " << setup.partialNote << "\n\n";
  md << "- Size " << setup.width << "x" << setup.height << ", " << setup.budget << ", " << setup.runs
     << " independent run(s) (seeds) per configuration, device " << setup.device << ".\n";
  md << "- Reference: " << setup.reference << "; mean RGB " << fmt("%.5f", refMean[0]) << " "
     << fmt("%.5f", refMean[1]) << " " << fmt("%.5f", refMean[2]) << ".\n";
  md << "- Errors are averaged over the runs; variance is the mean per-pixel variance between runs (the "
        "noise "
        "part of the MSE), bias^2 ~ MSE - variance (when the reference is itself a render, its own noise is "
        "part of this bias^2 floor). Each run's seed is an independent randomisation with every sampler "
        "(owen: "
        "its own Owen scrambles; sobol: every dimension its own random shift; pcg: its own hashes). Hybrid "
        "modes (`--mode hybrid|reflections`) count frames as spp; their bias^2 is what the approximation "
        "costs against the path-traced reference. Efficiency = 1 / (MSE x time).\n";
  for (const auto& note : setup.notes) md << "- " << note << "\n";
  std::vector<double> finals;
  for (const auto& r : results)
    if (!r.checkpoints.empty()) finals.push_back(mean(r.checkpoints.back().relMse));
  double target = setup.targetRelMse;
  if (target <= 0 && !finals.empty()) {
    std::sort(finals.begin(), finals.end());
    target = finals[finals.size() / 2];
  }
  md << "- Time to error: seconds to reach relMSE " << fmt("%.3g", target)
     << (setup.targetRelMse > 0 ? "" : " (the median of the final relMSEs)")
     << ", log-log interpolated between checkpoints. Times are those of the runs after the first where there "
        "are "
        "several: the first renders one sample per submission to find the checkpoints by time, waiting for "
        "the "
        "device after each (converge.csv's seconds_min and seconds_max span all runs).\n";
  if (!setup.plotNote.empty()) {
    md << "- **Plot missing:** " << setup.plotNote << "\n";
  } else {
    md << "- Plot: `converge.png` (log relMSE and log RMSE against log time). Data: `converge.csv`.\n";
  }
  md << "\n| config | flags | spp | time (s) | RMSE | relMSE | variance | bias^2 | mean RGB vs ref (%) | "
        "efficiency | time to relMSE "
     << fmt("%.3g", target) << " | NaN/Inf dropped | max/mean | >10x mean |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto row = [&](const ConfigResult& r, const std::vector<Checkpoint>& rows, const std::string& name) {
    if (rows.empty()) return;
    const auto& cp = rows.back();
    const double t = renderSeconds(cp), m = mean(cp.mse);
    const eval::Rgb mm = meanOfRuns(cp);
    std::string bias;
    for (int k = 0; k < 3; ++k)
      bias += (k ? " " : "") + fmt("%+.2f", refMean[k] != 0 ? 100.0 * (mm[k] / refMean[k] - 1.0) : 0.0);
    const auto ttr = timeToReach(rows, target);
    md << "| " << name << " | `" << (r.flags.empty() ? "(base)" : r.flags) << "` | " << cp.spp << " | "
       << secondsText(t) << " | " << fmt("%.4g", std::sqrt(m)) << " | " << fmt("%.4g", mean(cp.relMse))
       << " | " << fmt("%.3g", cp.variance) << " | " << fmt("%.3g", std::max(0.0, m - cp.variance)) << " | "
       << bias << " | " << fmt("%.4g", m > 0 && t > 0 ? 1.0 / (m * t) : 0.0) << " | "
       << (ttr ? secondsText(*ttr) : std::string("not reached")) << " | " << r.dropped << " | "
       << fmt("%.1f", r.fireflies.maxOverMean) << " | " << fmt("%.2g", r.fireflies.fractionAbove10x)
       << " |\n";
  };
  for (const auto& r : results) {
    row(r, r.checkpoints, r.denoised.empty() ? r.name : r.name + " (raw)");
    row(r, r.denoised, r.name + " (denoised)");
  }
  if (setup.moreSections) setup.moreSections(md);
  writeErrorImages(dir, results, reference, md);
  writeFileAtomically(dir / "converge.md", md.str(), "converge");  // last: it names the files above
}

}  // namespace wb::app
