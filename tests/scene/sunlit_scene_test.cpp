// The committed assets/sunlit_spheres.gltf (tools/make_default_scene, issue 29): a sun, a ground plane, a
// Lambert sphere and two GGX conductors of roughness 0.25 and 0.6; and its glossy reflectors
// (scene/reflectors.h): the smooth conductor alone, as a sphere that holds every one of its vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/paths.h"
#include "scene/reflectors.h"
#include "scene/scene.h"

namespace wb::scene {
namespace {

Scene loadSunlit() {
  return loadGltf(wb::defaultScenePath().parent_path() / "sunlit_spheres.gltf");
}

const gpu::Material& material(const Scene& scene, const std::string& name) {
  const auto it = std::find(scene.materialNames.begin(), scene.materialNames.end(), name);
  EXPECT_NE(it, scene.materialNames.end()) << name;
  return scene.materials.at(size_t(it - scene.materialNames.begin()));
}

}  // namespace

TEST(SunlitScene, HasTheSunGroundAndThreeSpheres) {
  const Scene scene = loadSunlit();
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
  EXPECT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.instances.size(), 4u);
  EXPECT_FLOAT_EQ(material(scene, "gold_roughness_0.25").roughness, 0.25f);
  EXPECT_FLOAT_EQ(material(scene, "gold_roughness_0.25").metallic, 1.0f);
  EXPECT_FLOAT_EQ(material(scene, "steel_roughness_0.6").roughness, 0.6f);
  EXPECT_FLOAT_EQ(material(scene, "lambert_sphere").metallic, 0.0f);
}

TEST(SunlitScene, TheSmoothConductorIsTheOnlyGlossyReflector) {
  const Scene scene = loadSunlit();
  EXPECT_TRUE(isGlossyReflector(material(scene, "gold_roughness_0.25")));
  EXPECT_FALSE(isGlossyReflector(material(scene, "steel_roughness_0.6")));
  EXPECT_FALSE(isGlossyReflector(material(scene, "ground")));
  const auto spheres = glossyReflectors(scene, scene.materials);
  ASSERT_EQ(spheres.size(), 1u);
  EXPECT_NEAR(spheres[0].x, 0.0f, 1e-3f);
  EXPECT_NEAR(spheres[0].y, 1.0f, 1e-3f);
  EXPECT_NEAR(spheres[0].z, -0.6f, 1e-3f);
  EXPECT_NEAR(spheres[0].w, 1.0f, 1e-2f);
  // Every vertex of the gold sphere lies inside the bounding sphere.
  for (const auto& inst : scene.instances) {
    if (inst.nodeName != "sphere_gold_0.25") continue;
    for (const auto& p : scene.meshes.at(size_t(inst.mesh)).primitives) {
      for (const auto& v : p.vertices) {
        const glm::vec3 w = glm::vec3(inst.transform * glm::vec4(v.position, 1.0f));
        EXPECT_LE(glm::length(w - glm::vec3(spheres[0])), spheres[0].w);
      }
    }
  }
  // A scene's materials edited live: a rough gold is no reflector.
  auto edited = scene.materials;
  for (auto& m : edited) m.roughness = std::max(m.roughness, 0.7f);
  EXPECT_TRUE(glossyReflectors(scene, edited).empty());
}

}  // namespace wb::scene
