// The convergence report's arithmetic, against hand-computed answers.
#include <gtest/gtest.h>

#include <cmath>

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

TEST(ConvergeReport, TimeToReachAveragesTheRuns) {
  ConfigResult r;
  // Runs average to (2 s, 0.1) and (20 s, 0.001): error ~ t^-2, so 0.01 is reached at 2 * sqrt(10) s.
  r.checkpoints = {at({1.0, 3.0}, {0.05, 0.15}), at({18.0, 22.0}, {0.0005, 0.0015})};
  EXPECT_NEAR(*timeToReach(r, 0.01), 2.0 * std::sqrt(10.0), 1e-9);
}

TEST(ConvergeReport, NamesAndNumbers) {
  EXPECT_EQ(safeName("no nee/mis"), "no_nee_mis");
  EXPECT_EQ(safeName("rr-0.5_x"), "rr-0_5_x");
  EXPECT_EQ(safeName(""), "config");
  EXPECT_DOUBLE_EQ(mean({1.0, 2.0, 6.0}), 3.0);
  EXPECT_DOUBLE_EQ(mean({}), 0.0);
  EXPECT_EQ(fmt("%.2f", 3.14159), "3.14");
}
