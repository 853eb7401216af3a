// The window's --set / script settings check numbers as the command-line flags do (one registry:
// render/parameters.h): finite and in the parameter's range.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "live/session_state.h"

namespace {

bool refused(const std::string& name, const std::string& value) {
  wb::live::SessionState st;
  try {
    wb::live::applySetting(st, name, value);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what()).find(name) != std::string::npos;
  }
  return false;
}

TEST(SessionState, NumericSettingsAreFiniteAndInRange) {
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"env_rotation", "nan"},
                                                        {"env_rotation", "inf"},
                                                        {"env_intensity", "nan"},
                                                        {"env_intensity", "-1"},
                                                        {"env_color", "1,nan,1"},
                                                        {"sun_angle", "-10"},
                                                        {"sun_angle", "95"},
                                                        {"ao_radius", "inf"},
                                                        {"reflection_roughness", "nan"},
                                                        {"reflection_metallic", "2"},
                                                        {"exposure", "nan"},
                                                        {"rr_min", "0"},
                                                        {"budget_ms", "-5"}})
    EXPECT_TRUE(refused(name, value)) << name << "=" << value;
  wb::live::SessionState st;
  wb::live::applySetting(st, "env_rotation", "90");
  wb::live::applySetting(st, "sun_angle", "2.5");
  wb::live::applySetting(st, "reflection_roughness", "0.25");
  wb::live::applySetting(st, "env_intensity", "1e30");
  EXPECT_FLOAT_EQ(st.params.render.envRotationDeg, 90.0f);
  EXPECT_FLOAT_EQ(st.params.render.sunAngleDeg, 2.5f);
  EXPECT_FLOAT_EQ(st.params.hybrid.reflectionMaxRoughness, 0.25f);
  EXPECT_FLOAT_EQ(st.params.render.envIntensity, 1e30f);
}

// One registry: the flag and the setting name the same parameter, with the same range.
TEST(SessionState, FlagsAndSettingsShareTheRanges) {
  for (const char* name : {"sun_angle", "reflection_roughness", "env_intensity", "rr_exponent"}) {
    const auto* p = wb::render::findParameter(name).info;
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(wb::render::findParameter(p->flag).info, p) << p->flag;
    EXPECT_TRUE(refused(name, "nan")) << name;
    EXPECT_TRUE(refused(name, std::to_string(p->max * 2 + 1))) << name;
    wb::live::SessionState st;
    wb::live::applySetting(st, p->flag.substr(2), std::to_string(p->min));  // by the flag's name
    EXPECT_EQ(p->get(st.params), wb::render::parseParameter(*p, std::to_string(p->min))) << name;
  }
}

}  // namespace
