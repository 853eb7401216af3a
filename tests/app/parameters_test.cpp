// The parameters' command-line flags and JSON (app/parameter_cli.h, app/parameter_json.h): generated from the
// registry, so every parameter has its flag and its key, and a bad value names the flag.
#include <gtest/gtest.h>

#include "app/parameter_cli.h"
#include "app/parameter_json.h"
#include "app/render_options.h"

using namespace wb;

namespace {

render::Parameters parse(std::vector<std::string> args) {
  CLI::App cli;
  app::ParameterFlags flags;
  render::Parameters p;
  flags.addTo(cli, p);
  std::reverse(args.begin(), args.end());
  cli.parse(args);
  flags.apply(p);
  return p;
}

}  // namespace

TEST(ParameterFlags, EveryFlagSetsItsParameter) {
  const auto p =
      parse({"--max-bounces", "3", "--no-nee", "--no-rr", "--env-color", "1,2,3", "--sampler", "pcg",
             "--mode", "hybrid", "--ao-rays", "5", "--no-temporal", "--exposure", "-1.5", "--generic"});
  EXPECT_EQ(p.render.maxBounces, 3u);
  EXPECT_FALSE(p.render.nee);
  EXPECT_FALSE(p.render.russianRoulette);
  EXPECT_TRUE(p.render.mis);
  EXPECT_EQ(p.render.envColor, glm::vec3(1, 2, 3));
  EXPECT_EQ(p.render.sampler, render::SamplerKind::Pcg);
  EXPECT_EQ(p.mode, render::RenderMode::Hybrid);
  EXPECT_EQ(p.hybrid.aoRays, 5u);
  EXPECT_FALSE(p.hybrid.temporal);
  EXPECT_FLOAT_EQ(p.display.exposure, -1.5f);
  EXPECT_TRUE(p.render.generic);
}

TEST(ParameterFlags, ABadValueNamesTheFlag) {
  for (const auto& info : render::parameterList()) {
    if (info.flag.empty() ||
        (info.type != render::ParameterType::Float && info.type != render::ParameterType::UInt))
      continue;
    try {
      parse({info.flag, "nan"});
      ADD_FAILURE() << info.flag << " accepted nan";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(info.flag + ":", 0), 0u) << e.what();
    }
  }
  EXPECT_THROW(parse({"--rr-min", "0.9", "--rr-max", "0.5"}), std::invalid_argument);
}

TEST(ParameterJson, EveryParameterUnderItsName) {
  render::Parameters p;
  p.render.envColor = {0.1f, 0.2f, 0.3f};
  const auto j = app::parametersJson(p);
  for (const auto& info : render::parameterList()) {
    ASSERT_TRUE(j.contains(info.name)) << info.name;
    switch (info.type) {
      case render::ParameterType::Bool:
        EXPECT_TRUE(j[info.name].is_boolean()) << info.name;
        break;
      case render::ParameterType::UInt:
      case render::ParameterType::Float:
        EXPECT_TRUE(j[info.name].is_number()) << info.name;
        break;
      case render::ParameterType::Color:
        EXPECT_TRUE(j[info.name].is_array() && j[info.name].size() == 3) << info.name;
        break;
      default:
        EXPECT_TRUE(j[info.name].is_string()) << info.name;
    }
  }
  EXPECT_EQ(j["sampler"], "owen");
  EXPECT_EQ(j["russian_roulette"], true);
  EXPECT_NEAR(j["env_color"][2].get<double>(), 0.3, 1e-6);
}
