// What a scene actually uses, so the path tracer is compiled for only that (scene-driven specialisation).
#pragma once
#include <string>
#include <vector>

#include "scene/scene.h"
#include "shader/types.h"
#include "shared/pathtracer_types.h"
#include "shared/scene_types.h"

namespace wb::scene {

// Its values are the shaders' (WB_ENV_MODE of the specialised path tracer, the environment lookup's kind).
enum class EnvironmentKind { None = WB_ENV_NONE, Constant = WB_ENV_CONSTANT, Map = WB_ENV_MAP };

struct SceneFeatures {
  bool alphaMask = true;
  bool alphaBlend = true;
  bool normalMaps = true;
  bool emissive = true;
  bool textures = true;
  bool specular =
      true;  // some material sets KHR_materials_specular values other than the defaults (1, white)
  bool reflectors = true;  // some material is a glossy reflector (scene/reflectors.h): reflector guiding
  // The generic build reads the light count at run time: there it only sizes the shadow requests of the path
  // payload (capacity kGenericMaxLights, or this when more).
  uint32_t directionalLights = 0;
  EnvironmentKind environment = EnvironmentKind::Map;
  bool generic = true;  // the all-features build: every branch compiled in, light count read at run time
  // The glTF extensions the scene's file uses (informational: the code they need is decided by the flags
  // above, so two scenes with the same flags share compiled variants).
  std::vector<std::string> extensions;
  std::vector<shader::Define> extraDefines;  // the user's `--define K=V`, appended to the feature defines

  bool anyAlpha() const { return alphaMask || alphaBlend; }
  bool operator==(const SceneFeatures&) const = default;
};

// Directional lights the generic build shades without a define (the shaders' WB_GENERIC_MAX_LIGHTS).
inline constexpr uint32_t kGenericMaxLights = WB_GENERIC_MAX_LIGHTS;

// The all-features build (`--generic`), for comparison and as a fallback; pass the scene's directional light
// count so a scene with more than kGenericMaxLights gets room for all of them.
SceneFeatures genericFeatures(uint32_t directionalLights = 0);
// Analyses the scene (materials, textures, lights) and the environment the render will use.
SceneFeatures analyzeFeatures(const Scene& scene, EnvironmentKind environment);
// Whether a build for `f` renders `materials` as they are (a live edit may add emission or specular factors
// that a specialised build compiled out).
bool featuresCover(const SceneFeatures& f, const std::vector<gpu::Material>& materials);
// Shader defines for a feature set: part of every stage's variant key, so variants are cached like any other.
std::vector<shader::Define> featureDefines(const SceneFeatures& f);
// One line for logs and the UI, e.g. "lights=1 env=constant mask normal-maps emissive textures".
std::string describeFeatures(const SceneFeatures& f);

}  // namespace wb::scene
