// The convergence report's arithmetic, against hand-computed answers; raw and denoised side by side.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/converge_denoise.h"
#include "app/converge_report.h"

using namespace wb::app;

namespace {

Checkpoint at(std::vector<double> seconds, std::vector<double> relMse) {
  Checkpoint c;
  c.seconds = std::move(seconds);
  c.relMse = std::move(relMse);
  return c;
}

}  // namespace

TEST(ConvergeReport, TimeToReachInterpolatesInLogLog) {
  ConfigResult r;
  r.checkpoints = {at({1.0}, {0.1}), at({10.0}, {0.01})};
  // Error ~ 1/t between the two: the geometric mean of the errors is reached at the geometric mean of the
  // times.
  EXPECT_NEAR(*timeToReach(r, std::sqrt(0.1 * 0.01)), std::sqrt(10.0), 1e-9);
  EXPECT_NEAR(*timeToReach(r, 0.01), 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(*timeToReach(r, 0.5), 1.0);  // met at the first checkpoint already
  EXPECT_FALSE(timeToReach(r, 0.001).has_value());
  EXPECT_FALSE(timeToReach(ConfigResult{}, 0.1).has_value());
}

// Errors average over every run; times over the runs after the first, which waits for the device after each
// sample (renderSeconds).
TEST(ConvergeReport, TimeToReachAveragesTheRunsAfterTheFirstForTime) {
  ConfigResult r;
  // (2 s, 0.1) and (20 s, 0.001): error ~ t^-2, so 0.01 is reached at 2 * sqrt(10) s. The first run's times
  // (5 s and 50 s) would make it 3 * sqrt(10) s.
  r.checkpoints = {at({5.0, 1.0, 3.0}, {0.1, 0.05, 0.15}), at({50.0, 18.0, 22.0}, {0.001, 0.0005, 0.0015})};
  EXPECT_NEAR(*timeToReach(r, 0.01), 2.0 * std::sqrt(10.0), 1e-9);
  EXPECT_DOUBLE_EQ(renderSeconds(r.checkpoints[0]), 2.0);
  EXPECT_DOUBLE_EQ(renderSeconds(at({4.0}, {0.1})), 4.0) << "one run: its time";
  EXPECT_DOUBLE_EQ(renderSeconds(Checkpoint{}), 0.0);
}

TEST(ConvergeReport, NamesAndNumbers) {
  EXPECT_EQ(safeName("no nee/mis"), "no_nee_mis");
  EXPECT_EQ(safeName("rr-0.5_x"), "rr-0_5_x");
  EXPECT_EQ(safeName(""), "config");
  EXPECT_DOUBLE_EQ(mean({1.0, 2.0, 6.0}), 3.0);
  EXPECT_DOUBLE_EQ(mean({}), 0.0);
  EXPECT_EQ(fmt("%.2f", 3.14159), "3.14");
  EXPECT_EQ(secondsText(0.014318), "0.0143");
  EXPECT_EQ(secondsText(2.4321), "2.43");
  EXPECT_EQ(secondsText(1234.56), "1235");
}

namespace {

Checkpoint measured(uint32_t spp, double seconds, double relMse, wb::eval::Rgb mean) {
  Checkpoint c = at({seconds}, {relMse});
  c.spp = spp;
  c.mse = {relMse};
  c.mean = {mean};
  return c;
}

}  // namespace

TEST(ConvergeReport, DenoiseVerdictComparesRawAndDenoisedOfTheSameSamples) {
  ConfigResult r;
  r.name = "denoised";
  // Raw: relMSE 0.1 at 1 s, 0.001 at 100 s (0.01 at 10 s). Denoised: 0.02 at 1.5 s, 0.0005 at 101 s.
  r.checkpoints = {measured(1, 1.0, 0.1, {1, 1, 1}), measured(100, 100.0, 0.001, {1.0, 2.0, 4.0})};
  r.denoised = {measured(1, 1.5, 0.02, {1, 1, 1}), measured(100, 101.0, 0.0005, {1.0005, 2.0, 3.996})};
  const DenoiseVerdict v = denoiseVerdict(r);
  ASSERT_TRUE(v.rawSeconds && v.denoisedSeconds && v.timeRatio);
  EXPECT_NEAR(*v.rawSeconds, 10.0, 1e-9);
  EXPECT_LT(*v.denoisedSeconds, 10.0);
  EXPECT_NEAR(*v.timeRatio, *v.denoisedSeconds / 10.0, 1e-12);
  EXPECT_TRUE(v.neverWorse);
  EXPECT_NEAR(v.worstRatio, 0.5, 1e-12);
  EXPECT_EQ(v.worstSpp, 100u);
  EXPECT_NEAR(v.finalMeanDifference, 0.001, 1e-9);  // blue: 3.996 / 4 - 1
  // One checkpoint where the denoised image is worse: said.
  r.denoised[1].relMse = {0.002};
  EXPECT_FALSE(denoiseVerdict(r).neverWorse);
  EXPECT_NEAR(denoiseVerdict(r).worstRatio, 2.0, 1e-12);
}

TEST(ConvergeReport, TheCsvHasRawAndDenoisedRowsAndTheMarkdownSideBySide) {
  ConfigResult r;
  r.name = "dn";
  r.checkpoints = {measured(1, 1.0, 0.1, {1, 1, 1}), measured(2, 2.0, 0.05, {1, 1, 1})};
  r.denoised = {measured(1, 1.1, 0.01, {1, 1, 1}), measured(2, 2.1, 0.008, {1, 1, 1})};
  r.denoised[1].offReference.runs = 4;
  r.denoised[1].offReference.pixels = 100;
  r.denoised[1].offReference.significant = 3;
  const auto path = std::filesystem::temp_directory_path() / ("wb_converge_dn_" + std::to_string(::getpid()));
  writeCsv(path, {r}, {1, 1, 1});
  std::ifstream f(path);
  std::string header, line;
  std::getline(f, header);
  EXPECT_NE(header.find(",image,pixels_significant,pixels_significant_vs_raw,pixel_test_alpha"),
            std::string::npos);
  int raw = 0, denoised = 0;
  while (std::getline(f, line)) {
    if (line.find(",raw,") != std::string::npos) ++raw;
    if (line.find(",denoised,0.03,") != std::string::npos) ++denoised;  // 3 of 100 pixels significant
    if (line.find(",denoised,,") != std::string::npos) ++denoised;      // not tested
  }
  EXPECT_EQ(raw, 2);
  EXPECT_EQ(denoised, 2);
  std::filesystem::remove(path);
  std::ostringstream md;
  writeDenoiseComparison(md, {r});
  EXPECT_NE(md.str().find("| 2 | 0.05 | 0.008 | 0.160 |"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("3.00%"), std::string::npos) << md.str();
}
