// The hard-case scenes of `converge --hard-cases` (src/scene/hard_cases.h) as data: enough cases with unique
// names and flag variants, every setting a registry parameter under its own name with a value the registry
// accepts, and the environments and bounce limits the furnaces need. Rendering them:
// tests/eval/hard_cases_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "render/parameters.h"
#include "scene/hard_cases.h"

using namespace wb;

TEST(HardCaseScenes, TenOrMoreWithUniqueNamesEachWithVariants) {
  const auto cases = scene::hardCases();
  EXPECT_GE(cases.size(), 10u);
  std::set<std::string> names;
  for (const auto& hc : cases) {
    EXPECT_TRUE(names.insert(hc.name).second) << hc.name;
    EXPECT_FALSE(hc.variants.empty()) << hc.name;
    EXPECT_FALSE(hc.scene.meshes.empty()) << hc.name;
  }
}

TEST(HardCaseScenes, EverySettingIsARegistryParameterByNameWithAValidValue) {
  for (const auto& hc : scene::hardCases()) {
    for (const auto& setting : hc.settings) {
      SCOPED_TRACE(hc.name + ": " + setting);
      const auto nameValue = render::splitAssignment(setting);
      ASSERT_TRUE(nameValue);
      const render::ParameterMatch m = render::findParameter(nameValue->first);
      ASSERT_NE(m.info, nullptr) << "unknown parameter";
      EXPECT_EQ(m.info->name, nameValue->first) << "a registry name, not a flag or another spelling";
      render::Parameters p;
      EXPECT_NO_THROW(render::setParameters(p, {setting}));
    }
  }
}

TEST(HardCaseScenes, FurnacesHaveAUniformWhiteEnvironmentAndLongPaths) {
  size_t furnaces = 0;
  for (const auto& hc : scene::hardCases()) {
    SCOPED_TRACE(hc.name);
    render::Parameters p;  // a user's environment, replaced by the case's
    p.render.envPath = "user.hdr";
    p.render.envColor = glm::vec3(0.2f, 0.3f, 0.4f);
    p.render.envIntensity = 3.0f;
    render::setParameters(p, hc.settings);
    if (hc.name == "tiny-sun-hdr") {
      EXPECT_TRUE(std::filesystem::is_regular_file(p.render.envPath)) << p.render.envPath;
      EXPECT_EQ(p.render.envIntensity, 1.0f);
      continue;
    }
    ++furnaces;
    EXPECT_TRUE(p.render.envPath.empty());
    EXPECT_EQ(p.render.envColor, glm::vec3(1.0f));
    EXPECT_EQ(p.render.envIntensity, 1.0f);
    EXPECT_GE(std::max(p.render.maxBounces, hc.minBounces), 64u);
    if (hc.name == "mirror-corridor") {
      EXPECT_EQ(p.render.maxBounces, 256u);
    }
  }
  EXPECT_GE(furnaces, 10u);
}
