// The hard-case suite of `converge --hard-cases` (src/scene/hard_cases.cpp), run as a test at small size: no
// case and configuration drops a NaN/Inf sample or leaves a non-finite pixel, energy-preserving furnaces stay
// at 1, and no furnace creates energy beyond the known single-scattering dielectric excess (~2%).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <sstream>

#include <CLI/CLI.hpp>

#include "app/cmd_converge.h"
#include "app/render_options.h"
#include "eval/metrics.h"
#include "gpu_fixture.h"

using namespace wb;

namespace {

// The variant's flags at 16x16 and 16 spp, with the case's settings over them as converge applies them.
render::RenderSettings settingsFor(const scene::HardCase& hc, const std::string& variant) {
  app::RenderOptions ro;
  CLI::App cli;
  app::addRenderOptions(cli, ro);
  std::vector<std::string> args;
  std::istringstream ss(variant);
  for (std::string w; ss >> w;) args.push_back(w);
  std::reverse(args.begin(), args.end());
  cli.parse(args);
  ro.size = "16x16";
  app::finishRenderOptions(ro);
  ro.params.render.spp = 16;
  app::applyHardCase(hc, ro.params);
  return ro.params.render;
}

std::vector<std::string> hardCaseNames() {
  std::vector<std::string> names;
  for (const auto& hc : scene::hardCases()) names.push_back(hc.name);
  return names;
}

}  // namespace

// One test per case, each of its flag variants in turn.
class HardCase : public ::testing::TestWithParam<std::string> {};

TEST_P(HardCase, NoNanOrInfAndFurnacesHoldTheirEnergy) {
  // Furnaces whose materials preserve energy exactly (Lambert, a perfect mirror): their mean is the furnace
  // value within noise. Single-scattering GGX (rough metal, the dielectric's specular layer) loses or gains a
  // few percent by design and is only held to "no more than 3% created".
  const std::set<std::string> exact = {"grazing-lambert", "metal-rough0",         "scale-1e-3",
                                       "scale-1e5",       "degenerate-triangles", "broken-tangents",
                                       "alpha-foliage",   "opaque-leaves-control"};
  const auto cases = scene::hardCases();
  const auto it =
      std::find_if(cases.begin(), cases.end(), [](const scene::HardCase& c) { return c.name == GetParam(); });
  ASSERT_NE(it, cases.end());
  const auto& hc = *it;
  for (const auto& variant : hc.variants) {
    SCOPED_TRACE(hc.name + " " + variant);
    render::SessionOptions o;
    o.sceneData = hc.scene;
    o.settings = settingsFor(hc, variant);
    o.quiet = true;
    auto session = wb::testing::makeSession(o);
    session->render(o.settings.spp);
    const auto img = session->image();
    EXPECT_EQ(session->pathTracer().readCounters().droppedSamples, 0u);
    EXPECT_EQ(eval::countNonFinite(img), 0u);
    wb::testing::expectNoValidationErrors(*session);
    if (hc.furnaceValue <= 0) continue;
    const auto m = eval::meanRgb(img);
    for (int c = 0; c < 3; ++c) {
      const double rel = m[c] / hc.furnaceValue - 1.0;
      EXPECT_LT(rel, 0.03) << "energy created, channel " << c;
      // Default flags only: --no-mis cannot reach a delta lobe by design (see the case notes).
      if (variant.empty() && exact.count(hc.name)) {
        EXPECT_NEAR(rel, 0.0, 0.02) << "channel " << c;
      }
    }
    if (hc.name == "mirror-corridor" && variant == "--no-rr") {
      EXPECT_NEAR(m[0], hc.furnaceValue, 0.01);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Suite, HardCase, ::testing::ValuesIn(hardCaseNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string n = info.param;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });
