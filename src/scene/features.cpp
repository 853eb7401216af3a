#include "scene/features.h"

#include "scene/reflectors.h"

namespace wb::scene {

SceneFeatures genericFeatures(uint32_t directionalLights) {
  SceneFeatures f;
  f.directionalLights = directionalLights;
  return f;
}

SceneFeatures analyzeFeatures(const Scene& scene, EnvironmentKind environment) {
  SceneFeatures f;
  f.generic = false;
  f.alphaMask = f.alphaBlend = f.normalMaps = f.emissive = f.textures = f.specular = f.reflectors = false;
  f.extensions = scene.extensionsUsed;
  // Only materials that some primitive uses count.
  std::vector<bool> used(scene.materials.size(), false);
  for (const auto& mesh : scene.meshes) {
    for (const auto& p : mesh.primitives) {
      if (p.material >= 0 && size_t(p.material) < used.size()) used[p.material] = true;
    }
  }
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    if (!used[i]) continue;
    const auto& m = scene.materials[i];
    f.alphaMask = f.alphaMask || m.alphaMode == WB_ALPHA_MASK;
    f.alphaBlend = f.alphaBlend || m.alphaMode == WB_ALPHA_BLEND;
    f.normalMaps = f.normalMaps || m.normalTexture >= 0;
    f.emissive = f.emissive || m.emissive.x > 0.0f || m.emissive.y > 0.0f || m.emissive.z > 0.0f;
    f.specular = f.specular || m.specularFactor != 1.0f || m.specularColorFactor != glm::vec3(1.0f);
    f.textures = f.textures || m.baseColorTexture >= 0 || m.normalTexture >= 0 ||
                 m.metallicRoughnessTexture >= 0 || m.emissiveTexture >= 0;
    f.reflectors = f.reflectors || isGlossyReflector(m);
  }
  f.directionalLights = static_cast<uint32_t>(scene.lights.size());
  f.environment = environment;
  return f;
}

bool featuresCover(const SceneFeatures& f, const std::vector<gpu::Material>& materials) {
  if (f.generic) return true;
  for (const auto& m : materials) {
    if (m.emissive != glm::vec3(0.0f) && !f.emissive) return false;
    if ((m.specularFactor != 1.0f || m.specularColorFactor != glm::vec3(1.0f)) && !f.specular) return false;
    if (isGlossyReflector(m) && !f.reflectors) return false;
  }
  return true;
}

std::vector<shader::Define> featureDefines(const SceneFeatures& f) {
  std::vector<shader::Define> out;
  if (f.generic) {
    out = {{"WB_GENERIC", "1"}};
    if (f.directionalLights > kGenericMaxLights) {
      out.push_back({"WB_GENERIC_MAX_LIGHTS", std::to_string(f.directionalLights) + "u"});
    }
    out.insert(out.end(), f.extraDefines.begin(), f.extraDefines.end());
    return out;
  }
  auto flag = [](bool b) { return std::string(b ? "1" : "0"); };
  out = {
      {"WB_SPECIALIZED", "1"},
      {"WB_HAS_ALPHA_MASK", flag(f.alphaMask)},
      {"WB_HAS_ALPHA_BLEND", flag(f.alphaBlend)},
      {"WB_HAS_NORMAL_MAPS", flag(f.normalMaps)},
      {"WB_HAS_EMISSIVE", flag(f.emissive)},
      {"WB_HAS_TEXTURES", flag(f.textures)},
      {"WB_HAS_SPECULAR", flag(f.specular)},
      {"WB_HAS_REFLECTORS", flag(f.reflectors)},
      {"WB_LIGHT_COUNT", std::to_string(f.directionalLights) + "u"},
      {"WB_ENV_MODE", std::to_string(static_cast<int>(f.environment))},
  };
  out.insert(out.end(), f.extraDefines.begin(), f.extraDefines.end());
  return out;
}

std::string describeFeatures(const SceneFeatures& f) {
  std::string extra;
  for (const auto& d : f.extraDefines) extra += " -D" + d.name + (d.value.empty() ? "" : "=" + d.value);
  if (f.generic) return "generic (all features)" + extra;
  std::string s = "lights=" + std::to_string(f.directionalLights) + " env=" +
                  (f.environment == EnvironmentKind::None       ? "none"
                   : f.environment == EnvironmentKind::Constant ? "constant"
                                                                : "map");
  if (f.alphaMask) s += " alpha-mask";
  if (f.alphaBlend) s += " alpha-blend";
  if (f.normalMaps) s += " normal-maps";
  if (f.emissive) s += " emissive";
  if (f.textures) s += " textures";
  if (f.specular) s += " specular";
  if (f.reflectors) s += " reflectors";
  for (const auto& e : f.extensions) s += " " + e;
  return s + extra;
}

}  // namespace wb::scene
