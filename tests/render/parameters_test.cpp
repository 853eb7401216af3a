// The parameter registry (render/parameters.h): every parameter round-trips through its text form, refuses
// what is out of range or not finite, is found under its name and its flag, and the image key follows the
// parameters that change the image.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "render/parameters.h"

using namespace wb::render;

TEST(Parameters, NamesAndFlagsAreUniqueAndEveryOneRoundTrips) {
  std::set<std::string> names, flags;
  const Parameters defaults;
  for (const auto& p : parameterList()) {
    EXPECT_TRUE(names.insert(p.name).second) << p.name;
    if (!p.flag.empty()) {
      EXPECT_TRUE(flags.insert(p.flag).second) << p.flag;
    }
    EXPECT_FALSE(p.help.empty()) << p.name;
    EXPECT_TRUE(p.get && p.put) << p.name;
    if (p.type == ParameterType::Bool) continue;
    // The default's text parses back to the default (sun_angle's -1 means "the scene's" and is no valid
    // input).
    if (p.name == "sun_angle") continue;
    Parameters copy = defaults;
    setParameter(copy, p.name, formatParameter(p, defaults));
    EXPECT_EQ(p.get(copy), p.get(defaults)) << p.name;
  }
  EXPECT_GE(names.size(), 25u);
  for (const char* required :
       {"max_bounces", "rr_start", "rr_min", "rr_max", "russian_roulette", "nee", "mis", "sampler", "seed",
        "mode", "env_intensity", "exposure", "tonemap", "view"})
    EXPECT_TRUE(names.count(required)) << required;
}

TEST(Parameters, NumbersMustBeFiniteAndInRange) {
  for (const auto& p : parameterList()) {
    if (p.type != ParameterType::Float && p.type != ParameterType::UInt && p.type != ParameterType::Color)
      continue;
    for (const std::string bad : {"nan", "inf", "-inf", "", "1e999", "abc"}) {
      const std::string text = p.type == ParameterType::Color ? bad + ",1,1" : bad;
      EXPECT_THROW(parseParameter(p, text), std::invalid_argument) << p.name << " accepted '" << text << "'";
    }
    if (p.min > -1e30) {
      const std::string below = std::to_string(p.min - 1.0);
      EXPECT_THROW(parseParameter(p, p.type == ParameterType::Color ? below + ",1,1" : below),
                   std::invalid_argument)
          << p.name;
    }
    if (p.max < 1e30 && p.type != ParameterType::Color) {
      EXPECT_THROW(parseParameter(p, std::to_string(p.max + 1.0)), std::invalid_argument) << p.name;
    }
  }
  try {
    parseParameter(*findParameter("sun_angle").info, "-10");
    ADD_FAILURE() << "a negative sun angle was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sun_angle"), std::string::npos)
        << "the message names the parameter";
  }
}

TEST(Parameters, SetFindsNamesAndFlagsAndKeepsTheRules) {
  Parameters p;
  setParameter(p, "max-bounces", "3");
  EXPECT_EQ(p.render.maxBounces, 3u);
  setParameter(p, "--rr-start", "1");
  EXPECT_EQ(p.render.rrStart, 1u);
  setParameter(p, "no_rr", "on");  // the flag --no-rr
  EXPECT_FALSE(p.render.russianRoulette);
  setParameter(p, "russian_roulette", "on");
  EXPECT_TRUE(p.render.russianRoulette);
  setParameter(p, "nee", "off");
  setParameter(p, "no-mis", "");  // a flag given without a value
  EXPECT_FALSE(p.render.nee);
  EXPECT_FALSE(p.render.mis);
  setParameter(p, "sampler", "pcg");
  EXPECT_EQ(p.render.sampler, SamplerKind::Pcg);
  setParameter(p, "mode", "reflections");
  EXPECT_EQ(p.mode, RenderMode::Reflections);
  setParameter(p, "env_color", "1,0.5,0");
  EXPECT_EQ(p.render.envColor, glm::vec3(1.0f, 0.5f, 0.0f));
  // rr_min above rr_max breaks a rule between parameters: refused, nothing changes.
  const Parameters before = p;
  EXPECT_THROW(setParameter(p, "rr_min", "0.99"), std::invalid_argument);
  EXPECT_EQ(p.render.rrMin, before.render.rrMin);
  EXPECT_THROW(setParameter(p, "bounces", "3"), std::invalid_argument);
  EXPECT_THROW(setParameter(p, "sampler", "halton"), std::invalid_argument);
}

TEST(Parameters, NameEqualsValueTextsApplyInTurnThroughSetParameter) {
  EXPECT_EQ(splitAssignment("env=a=b.hdr"), std::make_pair(std::string("env"), std::string("a=b.hdr")));
  EXPECT_EQ(splitAssignment("env="), std::make_pair(std::string("env"), std::string()));
  EXPECT_FALSE(splitAssignment("max_bounces"));
  Parameters p;
  setParameters(p, {"max_bounces=3", "no_rr=on", "env_color=1,0.5,0", "max_bounces=5"});
  EXPECT_EQ(p.render.maxBounces, 5u);
  EXPECT_FALSE(p.render.russianRoulette);
  EXPECT_EQ(p.render.envColor, glm::vec3(1.0f, 0.5f, 0.0f));
  for (const std::string bad : {"bounces=3", "max_bounces", "max_bounces=-1", "rr_min=0.99"}) {
    Parameters q;
    EXPECT_THROW(setParameters(q, {bad}), std::invalid_argument) << bad;
  }
}

TEST(Parameters, TheImageKeyFollowsWhatChangesTheImage) {
  Parameters a;
  Parameters b = a;
  b.display.exposure = 2.0f;  // display only
  b.render.spp = 99;          // how long, not what
  EXPECT_EQ(imageKey(a), imageKey(b));
  EXPECT_TRUE(changedParameters(a, b).empty());
  b.render.seed = 7;
  b.hybrid.aoRays = 5;
  EXPECT_NE(imageKey(a), imageKey(b));
  std::set<std::string> changed;
  for (const auto* p : changedParameters(a, b)) changed.insert(p->name);
  EXPECT_EQ(changed, (std::set<std::string>{"seed", "ao_rays"}));
}
