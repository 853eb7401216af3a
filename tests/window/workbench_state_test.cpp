// The window's --set / script settings check numbers as the command-line flags do (app/render_options.h):
// finite and in the parameter's range.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "app/render_options.h"
#include "app/window/workbench_state.h"

namespace {

bool refused(const std::string& name, const std::string& value) {
  wb::app::WorkbenchState st;
  try {
    wb::app::applySetting(st, name, value);
  } catch (const std::invalid_argument& e) {
    return std::string(e.what()).find(name) != std::string::npos;
  }
  return false;
}

TEST(WorkbenchState, NumericSettingsAreFiniteAndInRange) {
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
  wb::app::WorkbenchState st;
  wb::app::applySetting(st, "env_rotation", "90");
  wb::app::applySetting(st, "sun_angle", "2.5");
  wb::app::applySetting(st, "reflection_roughness", "0.25");
  wb::app::applySetting(st, "env_intensity", "1e30");
  EXPECT_FLOAT_EQ(st.settings.envRotationDeg, 90.0f);
  EXPECT_FLOAT_EQ(st.hybrid.sunAngleDeg, 2.5f);
  EXPECT_FLOAT_EQ(st.hybrid.reflectionMaxRoughness, 0.25f);
  EXPECT_FLOAT_EQ(st.settings.envIntensity, 1e30f);
}

// One table: the flag and the setting name the same parameter and range.
TEST(WorkbenchState, FlagsAndSettingsShareTheRanges) {
  using namespace wb::app;
  for (const ParamRange* p : {&params::kSunAngle, &params::kReflectionRoughness, &params::kEnvIntensity}) {
    EXPECT_THROW(parseParam(*p, "nan", p->flag), std::invalid_argument) << p->flag;
    EXPECT_THROW(parseParam(*p, std::to_string(p->max * 2 + 1), p->flag), std::invalid_argument) << p->flag;
    EXPECT_DOUBLE_EQ(parseParam(*p, std::to_string(p->min), p->flag), p->min);
  }
}

}  // namespace
