// The path inspector's window parts on the CPU: the projection that draws recorded paths over the image is
// the inverse of the camera ray through a pixel, its settings are checked, and its script command reaches the
// host.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "app/window/path_inspector_view.h"
#include "app/window/pixel_picker.h"
#include "app/window/script.h"
#include "live/session_state.h"

TEST(InspectorView, PathPointsProjectOntoThePixelTheirCameraRayLeaves) {
  wb::render::CameraState cam;
  cam.view = glm::lookAt(glm::vec3(1.0f, 2.0f, 5.0f), glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0, 1, 0));
  cam.yfov = 0.8f;
  cam.znear = 0.05f;
  for (auto [px, py] : {std::pair{10.5f, 20.5f}, std::pair{100.25f, 3.75f}, std::pair{0.5f, 79.5f}}) {
    glm::vec3 o, d;
    wb::app::cameraRay(cam, 160, 80, px, py, o, d);
    for (float t : {0.5f, 3.0f, 40.0f}) {
      const auto p = wb::app::projectToImage(cam, 160, 80, o + d * t);
      ASSERT_TRUE(p.has_value());
      EXPECT_NEAR(p->x, px, 2e-3f * (1.0f + t));
      EXPECT_NEAR(p->y, py, 2e-3f * (1.0f + t));
    }
    EXPECT_FALSE(wb::app::projectToImage(cam, 160, 80, o - d).has_value()) << "behind the camera";
  }
}

TEST(InspectorView, SettingsPickThePixelAndAreChecked) {
  wb::live::SessionState st;
  EXPECT_FALSE(st.inspectPixel.has_value());
  wb::live::applySetting(st, "inspect_pixel", "12,34");
  ASSERT_TRUE(st.inspectPixel.has_value());
  EXPECT_EQ(*st.inspectPixel, glm::uvec2(12, 34));
  wb::live::applySetting(st, "inspect_samples", "8");
  EXPECT_EQ(st.inspectSamples, 8u);
  wb::live::applySetting(st, "inspect_pixel", "off");
  EXPECT_FALSE(st.inspectPixel.has_value());
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, std::string>>{{"inspect_pixel", "12"},
                                                        {"inspect_pixel", "a,b"},
                                                        {"inspect_pixel", "-1,3"},
                                                        {"inspect_samples", "0"},
                                                        {"inspect_samples", "100000"}}) {
    EXPECT_THROW(wb::live::applySetting(st, name, value), std::invalid_argument) << name << "=" << value;
  }
}

namespace {

struct Host : wb::app::ScriptHost {
  void scriptSet(const std::string&, const std::string&) override {}
  void scriptScreenshot(const std::string&) override {}
  void scriptSave(const std::string&) override {}
  void scriptStats(const std::string&) override {}
  void scriptOrbit(float, float) override {}
  void scriptResize(int, int) override {}
  void scriptCommand(const std::string&) override {}
  void scriptInspect(const std::string& path) override { inspected = path; }
  size_t reloadCount() const override { return 0; }
  uint32_t samples() const override { return 0; }
  std::string inspected;
};

}  // namespace

TEST(InspectorView, InspectScriptCommandReachesTheHost) {
  wb::app::Script s;
  s.addLine("inspect /tmp/records.json", "test:1");
  Host h;
  EXPECT_FALSE(s.step(h));
  EXPECT_EQ(h.inspected, "/tmp/records.json");
  wb::app::Script missing;
  EXPECT_THROW(missing.addLine("inspect", "test:1"), std::runtime_error);
}
