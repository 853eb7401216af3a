#include "scene/material_conversion.h"

#include <cmath>

namespace wb::scene {
namespace {

float finiteOr(double value, float fallback) {
  return std::isfinite(value) ? static_cast<float>(value) : fallback;
}

double numberOr(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  return value.IsNumber() ? value.GetNumberAsDouble() : fallback;
}

glm::vec3 vec3Or(const tinygltf::Value& object, const char* key, glm::vec3 fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsArray() || value.ArrayLen() != 3) return fallback;
  glm::vec3 result;
  for (int i = 0; i < 3; ++i) {
    const tinygltf::Value& c = value.Get(i);
    result[i] = c.IsNumber() ? finiteOr(c.GetNumberAsDouble(), fallback[i]) : fallback[i];
  }
  return result;
}

class MaterialConverter {
 public:
  MaterialConverter(LoadContext& ctx, Scene& scene) : ctx_(ctx), scene_(scene) {}

  void convertImagesSamplersTextures() {
    const tinygltf::Model& model = ctx_.model();
    for (size_t i = 0; i < model.images.size(); ++i) {
      const tinygltf::Image& source = model.images[i];
      Image image;
      image.name = !source.name.empty() ? source.name : source.uri;
      const size_t expected = static_cast<size_t>(std::max(source.width, 0)) *
                              static_cast<size_t>(std::max(source.height, 0)) * 4;
      if (source.width > 0 && source.height > 0 && source.component == 4 && source.bits == 8 &&
          source.image.size() == expected) {
        image.width = source.width;
        image.height = source.height;
        image.rgba8.assign(source.image.begin(), source.image.end());
      }
      scene_.images.push_back(std::move(image));
    }
    for (const tinygltf::Sampler& source : model.samplers) {
      Sampler sampler;
      if (source.magFilter > 0) sampler.magFilter = source.magFilter;
      if (source.minFilter > 0) sampler.minFilter = source.minFilter;
      if (source.wrapS > 0) sampler.wrapS = source.wrapS;
      if (source.wrapT > 0) sampler.wrapT = source.wrapT;
      scene_.samplers.push_back(sampler);
    }
    for (size_t i = 0; i < model.textures.size(); ++i) {
      const tinygltf::Texture& source = model.textures[i];
      const std::string name = "texture " + std::to_string(i);
      Texture texture;
      // A texture without its image loses nothing but that texture (as an undecodable image does): exporters
      // leave such textures behind, often unused by any material.
      const bool imageMissing =
          source.source >= 0 && static_cast<size_t>(source.source) >= model.images.size();
      if (imageMissing) {
        ctx_.warn(name + " refers to image " + std::to_string(source.source) +
                  ", which does not exist; materials use their factors alone");
      }
      if (source.sampler >= 0 && static_cast<size_t>(source.sampler) >= model.samplers.size()) {
        ctx_.fail(name + " refers to sampler " + std::to_string(source.sampler) + ", which does not exist");
      }
      texture.sampler = source.sampler < 0 ? -1 : source.sampler;
      if (source.source >= 0 && !imageMissing &&
          scene_.images[static_cast<size_t>(source.source)].width > 0) {
        texture.image = source.source;
      }
      for (const auto& [extension, value] : source.extensions) {
        ctx_.warn(name + ": image source extension " + extension + " unsupported");
      }
      if (texture.image < 0 && !imageMissing)
        ctx_.warn(name + " has no decodable image; materials use their factors alone");
      scene_.textures.push_back(texture);
    }
    scene_.textureIsSrgb.assign(model.textures.size(), false);
  }

  int textureIndex(int index, int texCoord, const tinygltf::ExtensionMap& extensions,
                   const std::string& where, bool srgb) {
    if (index < 0) return -1;
    if (static_cast<size_t>(index) >= scene_.textures.size()) {
      ctx_.fail(where + " refers to texture " + std::to_string(index) + ", which does not exist");
    }
    if (texCoord != 0)
      ctx_.warn(where + ": texCoord " + std::to_string(texCoord) + " unsupported, TEXCOORD_0 used");
    if (extensions.count("KHR_texture_transform")) ctx_.warn(where + ": KHR_texture_transform ignored");
    if (scene_.textures[static_cast<size_t>(index)].image < 0) return -1;
    if (srgb) scene_.textureIsSrgb[static_cast<size_t>(index)] = true;
    return index;
  }

  void convertMaterials() {
    const tinygltf::Model& model = ctx_.model();
    for (size_t i = 0; i < model.materials.size(); ++i) {
      const tinygltf::Material& source = model.materials[i];
      const std::string name = source.name.empty() ? "material " + std::to_string(i) : source.name;
      const std::string where = "material '" + name + "'";
      const tinygltf::PbrMetallicRoughness& pbr = source.pbrMetallicRoughness;
      gpu::Material material = defaultMaterial();
      if (pbr.baseColorFactor.size() == 4) {
        for (int c = 0; c < 4; ++c)
          material.baseColorFactor[c] = finiteOr(pbr.baseColorFactor[size_t(c)], 1.0f);
      }
      material.metallic = finiteOr(pbr.metallicFactor, 1.0f);
      material.roughness = finiteOr(pbr.roughnessFactor, 1.0f);
      glm::vec3 emissive(0.0f);
      if (source.emissiveFactor.size() == 3) {
        for (int c = 0; c < 3; ++c) emissive[c] = finiteOr(source.emissiveFactor[size_t(c)], 0.0f);
      }
      if (source.alphaMode == "MASK") {
        material.alphaMode = WB_ALPHA_MASK;
      } else if (source.alphaMode == "BLEND") {
        material.alphaMode = WB_ALPHA_BLEND;
      } else {
        material.alphaMode = WB_ALPHA_OPAQUE;
      }
      material.alphaCutoff = finiteOr(source.alphaCutoff, 0.5f);
      material.flags = source.doubleSided ? WB_MATERIAL_DOUBLE_SIDED : 0u;
      material.baseColorTexture =
          textureIndex(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                       pbr.baseColorTexture.extensions, where + " baseColorTexture", true);
      material.metallicRoughnessTexture =
          textureIndex(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                       pbr.metallicRoughnessTexture.extensions, where + " metallicRoughnessTexture", false);
      material.normalTexture = textureIndex(source.normalTexture.index, source.normalTexture.texCoord,
                                            source.normalTexture.extensions, where + " normalTexture", false);
      material.normalScale = finiteOr(source.normalTexture.scale, 1.0f);
      material.emissiveTexture =
          textureIndex(source.emissiveTexture.index, source.emissiveTexture.texCoord,
                       source.emissiveTexture.extensions, where + " emissiveTexture", true);
      if (source.occlusionTexture.index >= 0) ctx_.warn(where + ": occlusionTexture ignored (path tracer)");

      float emissiveStrength = 1.0f;
      for (const auto& [extension, value] : source.extensions) {
        if (extension == "KHR_materials_emissive_strength") {
          emissiveStrength = finiteOr(numberOr(value, "emissiveStrength", 1.0), 1.0f);
        } else if (extension == "KHR_materials_specular") {
          material.specularFactor = finiteOr(numberOr(value, "specularFactor", 1.0), 1.0f);
          material.specularColorFactor = vec3Or(value, "specularColorFactor", glm::vec3(1.0f));
          if (value.IsObject() && (value.Has("specularTexture") || value.Has("specularColorTexture"))) {
            ctx_.warn(where + ": KHR_materials_specular textures ignored (factors used)");
          }
        } else {
          ctx_.warn(where + ": extension " + extension + " unsupported, ignored");
        }
      }
      material.emissive = emissive * emissiveStrength;
      scene_.materials.push_back(material);
      scene_.materialNames.push_back(name);
    }
  }

 private:
  LoadContext& ctx_;
  Scene& scene_;
};

}  // namespace

gpu::Material defaultMaterial() {
  gpu::Material material{};
  material.baseColorFactor = glm::vec4(1.0f);
  material.emissive = glm::vec3(0.0f);
  material.metallic = 1.0f;
  material.specularColorFactor = glm::vec3(1.0f);
  material.roughness = 1.0f;
  material.specularFactor = 1.0f;
  material.alphaCutoff = 0.5f;
  material.alphaMode = WB_ALPHA_OPAQUE;
  material.flags = 0u;
  material.baseColorTexture = material.normalTexture = -1;
  material.metallicRoughnessTexture = material.emissiveTexture = -1;
  material.normalScale = 1.0f;
  return material;
}

void convertMaterialsAndTextures(LoadContext& ctx, Scene& scene) {
  MaterialConverter converter(ctx, scene);
  converter.convertImagesSamplersTextures();
  converter.convertMaterials();
}

}  // namespace wb::scene
