// The heat-map legend's numbers and the cost views' scale, on the CPU.
#include <gtest/gtest.h>

#include "app/window/heat_legend.h"
#include "app/window/number_text.h"
#include "display/display_types.h"
#include "shared/pathtracer_types.h"

using wb::app::heatLegend;
using wb::app::legendNumber;

TEST(HeatLegend, NumbersHaveThreeDigitsAndThousandsAsTheStatsPanelPrintsThem) {
  EXPECT_EQ(legendNumber(0.0), "0");
  EXPECT_EQ(legendNumber(4.5), "4.5");
  EXPECT_EQ(legendNumber(0.0123456), "0.0123");
  EXPECT_EQ(legendNumber(999.4), "999");
  EXPECT_EQ(legendNumber(20553.3), "20.6 k");
  EXPECT_EQ(legendNumber(20553.3), wb::app::humanCount(20553.3));
  EXPECT_EQ(legendNumber(841528.5), "841.5 k");
  EXPECT_EQ(legendNumber(1034426.75), "1.03 M");
}

TEST(HeatLegend, TheCostViewsScaleIsTheNinetyFifthPercentile) {
  wb::eval::CostSummary cost;
  cost.clock = WB_CLOCK_SUBGROUP;
  cost.frame = 1e9;
  cost.p95 = 41000.0;
  cost.inefficiencyP95 = 0.25;
  const auto c = heatLegend(WB_VIEW_COST, 8.0f, &cost);
  ASSERT_TRUE(c.has_value());
  ASSERT_EQ(c->ticks.size(), 3u);
  EXPECT_EQ(c->ticks[1].second, "20.5 k");
  EXPECT_EQ(c->ticks[2].second, "41.0 k (p95)");
  EXPECT_NE(c->title.find("cycles"), std::string::npos) << c->title;
  EXPECT_NE(c->note.find("subgroup's slowest lane"), std::string::npos) << "lanes shared: " << c->note;
  cost.lanesIsolated = true;
  EXPECT_EQ(heatLegend(WB_VIEW_COST, 8.0f, &cost)->note, "red: the 5% most expensive pixels");
  const auto i = heatLegend(WB_VIEW_INEFFICIENCY, 8.0f, &cost);
  ASSERT_TRUE(i.has_value());
  EXPECT_EQ(i->ticks[2].second, "0.25 (p95)");
  EXPECT_FALSE(heatLegend(WB_VIEW_COST, 8.0f, nullptr).has_value()) << "no cost data: the panel says why";
}
