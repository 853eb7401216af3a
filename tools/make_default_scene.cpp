// Generates the workbench's default scene: a Cornell-style room (open at z = +1) with four spheres of
// different roughness/metalness, an alpha-masked leaf, an emissive ceiling panel and a sun shining in through
// the opening; and the sunlit glossy scene (writeSunlitScene). Usage: make_default_scene [output dir]
// (default: the project's assets/ folder)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <stb/stb_image_write.h>

#include "common/paths.h"

namespace {

using nlohmann::json;
constexpr float kPi = 3.14159265358979f;
constexpr int kFloat = 5126, kUShort = 5123;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

struct MeshData {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec4> tangents;
  std::vector<glm::vec2> uvs;
  std::vector<uint16_t> indices;

  void addTriangleFacing(uint16_t a, uint16_t b, uint16_t c, const glm::vec3& outward) {
    const glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    if (glm::dot(n, n) < 1e-14f) return;  // degenerate (sphere poles)
    if (glm::dot(n, outward) >= 0.0f) {
      indices.insert(indices.end(), {a, b, c});
    } else {
      indices.insert(indices.end(), {a, c, b});
    }
  }
};

// Handedness so that cross(n, t) * w points along increasing v.
float handedness(const glm::vec3& n, const glm::vec3& t, const glm::vec3& dPdv) {
  return glm::dot(glm::cross(n, t), dPdv) < 0.0f ? -1.0f : 1.0f;
}

// Quad o, o+a, o+a+b, o+b facing cross(a, b); the image's top row maps to the o+b edge.
void addQuad(MeshData& mesh, glm::vec3 o, glm::vec3 a, glm::vec3 b) {
  const glm::vec3 n = glm::normalize(glm::cross(a, b));
  const glm::vec3 t = glm::normalize(a);
  const float w = handedness(n, t, -b);
  const uint16_t base = static_cast<uint16_t>(mesh.positions.size());
  const glm::vec3 corners[4] = {o, o + a, o + a + b, o + b};
  const glm::vec2 uvs[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  for (int i = 0; i < 4; ++i) {
    mesh.positions.push_back(corners[i]);
    mesh.normals.push_back(n);
    mesh.tangents.push_back(glm::vec4(t, w));
    mesh.uvs.push_back(uvs[i]);
  }
  mesh.indices.insert(mesh.indices.end(), {base, uint16_t(base + 1), uint16_t(base + 2), base,
                                           uint16_t(base + 2), uint16_t(base + 3)});
}

// Unit UV sphere: u around (longitude), v from the north pole (v = 0) to the south pole.
MeshData makeSphere(int segments, int rings) {
  MeshData mesh;
  for (int i = 0; i <= rings; ++i) {
    const float theta = kPi * float(i) / float(rings);
    for (int j = 0; j <= segments; ++j) {
      const float phi = 2.0f * kPi * float(j) / float(segments);
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      const glm::vec3 t(-std::sin(phi), 0.0f, -std::cos(phi));  // d p / d phi, normalised
      const glm::vec3 dPdtheta(std::cos(theta) * std::cos(phi), -std::sin(theta),
                               -std::cos(theta) * std::sin(phi));
      mesh.positions.push_back(p);
      mesh.normals.push_back(p);
      mesh.tangents.push_back(glm::vec4(t, handedness(p, t, dPdtheta)));
      mesh.uvs.push_back(glm::vec2(float(j) / float(segments), float(i) / float(rings)));
    }
  }
  const auto index = [&](int i, int j) { return static_cast<uint16_t>(i * (segments + 1) + j); };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const uint16_t a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      const glm::vec3 centre =
          glm::normalize(mesh.positions[a] + mesh.positions[b] + mesh.positions[c] + mesh.positions[d]);
      mesh.addTriangleFacing(a, b, c, centre);
      mesh.addTriangleFacing(a, c, d, centre);
    }
  }
  return mesh;
}

// A 128x128 RGBA leaf: opaque inside the outline, alpha 0 outside (for alphaMode MASK).
std::vector<uint8_t> makeLeafImage(int size) {
  std::vector<uint8_t> rgba(size_t(size) * size * 4, 0);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float t = (float(y) + 0.5f) / float(size);  // 0 at the tip (top), 1 at the stem
      const float s = (float(x) + 0.5f) / float(size) - 0.5f;
      const float halfWidth = 0.36f * std::pow(std::sin(kPi * std::min(t / 0.88f, 1.0f)), 0.75f);
      const bool blade = t < 0.88f && std::abs(s) < halfWidth;
      const bool stem = t >= 0.8f && std::abs(s) < 0.018f;
      if (!blade && !stem) continue;
      glm::vec3 colour(0.20f, 0.50f, 0.12f);
      const float vein = std::abs(std::fmod(t * 9.0f + std::abs(s) * 12.0f, 1.0f) - 0.5f);
      if (std::abs(s) < 0.012f || stem) {
        colour = glm::vec3(0.55f, 0.65f, 0.25f);  // midrib and stem
      } else if (vein < 0.06f) {
        colour = glm::vec3(0.32f, 0.60f, 0.18f);  // side veins
      }
      if (blade)
        colour *= 0.85f + 0.15f * std::clamp(1.0f - std::abs(s) / std::max(halfWidth, 1e-3f), 0.0f, 1.0f);
      uint8_t* p = &rgba[(size_t(y) * size + x) * 4];
      for (int c = 0; c < 3; ++c)
        p[c] = static_cast<uint8_t>(std::lround(255.0f * std::min(colour[c], 1.0f)));
      p[3] = 255;
    }
  }
  return rgba;
}

class GltfWriter {
 public:
  json doc;

  GltfWriter() {
    doc["asset"] = {{"version", "2.0"}, {"generator", "rt_workbench tools/make_default_scene"}};
    doc["bufferViews"] = json::array();
    doc["accessors"] = json::array();
  }

  int addAccessor(const void* data, size_t bytes, int componentType, size_t count, const std::string& type,
                  int target, json min = nullptr, json max = nullptr) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    doc["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", bytes}, {"target", target}});
    const auto* begin = static_cast<const uint8_t*>(data);
    bin_.insert(bin_.end(), begin, begin + bytes);
    json accessor = {{"bufferView", doc["bufferViews"].size() - 1},
                     {"componentType", componentType},
                     {"count", count},
                     {"type", type}};
    if (!min.is_null()) accessor["min"] = min;
    if (!max.is_null()) accessor["max"] = max;
    doc["accessors"].push_back(accessor);
    return static_cast<int>(doc["accessors"].size() - 1);
  }

  // Adds the mesh's accessors and returns the primitive's JSON without material.
  json addMeshData(const MeshData& mesh) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : mesh.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    const size_t n = mesh.positions.size();
    const int position = addAccessor(mesh.positions.data(), n * 12, kFloat, n, "VEC3", kArrayBuffer,
                                     {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
    const int normal = addAccessor(mesh.normals.data(), n * 12, kFloat, n, "VEC3", kArrayBuffer);
    const int tangent = addAccessor(mesh.tangents.data(), n * 16, kFloat, n, "VEC4", kArrayBuffer);
    const int uv = addAccessor(mesh.uvs.data(), n * 8, kFloat, n, "VEC2", kArrayBuffer);
    const int indices = addAccessor(mesh.indices.data(), mesh.indices.size() * 2, kUShort,
                                    mesh.indices.size(), "SCALAR", kElementArrayBuffer);
    return {{"attributes",
             {{"POSITION", position}, {"NORMAL", normal}, {"TANGENT", tangent}, {"TEXCOORD_0", uv}}},
            {"indices", indices}};
  }

  int addMesh(const std::string& name, json primitives) {
    doc["meshes"].push_back({{"name", name}, {"primitives", primitives}});
    return static_cast<int>(doc["meshes"].size() - 1);
  }

  int addMaterial(json material) {
    doc["materials"].push_back(material);
    return static_cast<int>(doc["materials"].size() - 1);
  }

  int addNode(json node) {
    doc["nodes"].push_back(node);
    return static_cast<int>(doc["nodes"].size() - 1);
  }

  void write(const std::filesystem::path& dir, const std::string& stem) {
    doc["buffers"] = {{{"byteLength", bin_.size()}, {"uri", stem + ".bin"}}};
    std::ofstream(dir / (stem + ".gltf")) << doc.dump(1) << "\n";
    std::ofstream(dir / (stem + ".bin"), std::ios::binary)
        .write(reinterpret_cast<const char*>(bin_.data()), static_cast<std::streamsize>(bin_.size()));
  }

 private:
  std::vector<uint8_t> bin_;
};

json lambertian(const std::string& name, glm::vec3 albedo) {
  // Like ../shared/reference/cornell.gltf: no specular layer, so the BRDF is albedo / pi.
  return {{"name", name},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {albedo.r, albedo.g, albedo.b, 1.0}},
            {"metallicFactor", 0.0},
            {"roughnessFactor", 1.0}}},
          {"extensions", {{"KHR_materials_specular", {{"specularFactor", 0.0}}}}}};
}

json pbr(const std::string& name, glm::vec3 baseColor, float metallic, float roughness) {
  return {{"name", name},
          {"pbrMetallicRoughness",
           {{"baseColorFactor", {baseColor.r, baseColor.g, baseColor.b, 1.0}},
            {"metallicFactor", metallic},
            {"roughnessFactor", roughness}}}};
}

json quaternionJson(const glm::quat& q) {
  return {q.x, q.y, q.z, q.w};
}

// A directional light (KHR_lights_punctual, the document's only light) shining along `direction`; returns its
// node.
int addSun(GltfWriter& gltf, glm::vec3 direction, json colour, double intensity) {
  const glm::vec3 zAxis = -glm::normalize(direction);  // the node's -Z is the light's direction
  const glm::vec3 xAxis = glm::normalize(glm::cross(glm::vec3(0, 1, 0), zAxis));
  const glm::vec3 yAxis = glm::cross(zAxis, xAxis);
  const glm::quat rotation = glm::normalize(glm::quat_cast(glm::mat3(xAxis, yAxis, zAxis)));
  gltf.doc["extensions"] = {
      {"KHR_lights_punctual",
       {{"lights",
         {{{"name", "sun"}, {"type", "directional"}, {"color", colour}, {"intensity", intensity}}}}}}};
  return gltf.addNode({{"name", "sun"},
                       {"rotation", quaternionJson(rotation)},
                       {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
}

// The sunlit glossy scene (issue 29): a grey Lambert ground plane, a Lambert sphere and two GGX conductor
// spheres (roughness 0.25 and 0.6) of 3968 triangles each, lit by a delta sun; render it with the constant
// environment
// `--env-color 0.2,0.3,0.5` (glTF has no environment).
void writeSunlitScene(const std::filesystem::path& outDir) {
  GltfWriter gltf;
  gltf.doc["asset"]["generator"] = "rt_workbench tools/make_default_scene (sunlit spheres)";
  gltf.doc["extensionsUsed"] = {"KHR_materials_specular", "KHR_lights_punctual"};
  const int ground = gltf.addMaterial(lambertian("ground", glm::vec3(0.5f)));
  const int lambert = gltf.addMaterial(lambertian("lambert_sphere", glm::vec3(0.8f, 0.25f, 0.2f)));
  const int gold = gltf.addMaterial(pbr("gold_roughness_0.25", glm::vec3(1.0f, 0.766f, 0.336f), 1.0f, 0.25f));
  const int steel = gltf.addMaterial(pbr("steel_roughness_0.6", glm::vec3(0.56f, 0.57f, 0.58f), 1.0f, 0.6f));
  MeshData plane;
  addQuad(plane, {-20, 0, 20}, {40, 0, 0}, {0, 0, -40});  // y = 0, +Y
  json groundPrimitive = gltf.addMeshData(plane);
  groundPrimitive["material"] = ground;
  json rootNodes = json::array();
  rootNodes.push_back(
      gltf.addNode({{"name", "ground"}, {"mesh", gltf.addMesh("ground", json::array({groundPrimitive}))}}));
  const json spherePrimitive = gltf.addMeshData(makeSphere(64, 32));
  struct SphereSpec {
    const char* name;
    int material;
    glm::vec3 centre;
  };
  const SphereSpec spheres[] = {{"sphere_lambert", lambert, {-2.2f, 1.0f, 0.0f}},
                                {"sphere_gold_0.25", gold, {0.0f, 1.0f, -0.6f}},
                                {"sphere_steel_0.6", steel, {2.2f, 1.0f, 0.0f}}};
  for (const SphereSpec& s : spheres) {
    json primitive = spherePrimitive;
    primitive["material"] = s.material;
    rootNodes.push_back(gltf.addNode({{"name", s.name},
                                      {"mesh", gltf.addMesh(s.name, json::array({primitive}))},
                                      {"translation", {s.centre.x, s.centre.y, s.centre.z}}}));
  }
  rootNodes.push_back(addSun(gltf, glm::vec3(0.45f, -0.8f, -0.4f), {1.0, 0.97, 0.92}, 3.0));
  gltf.doc["cameras"] = {
      {{"name", "front"},
       {"type", "perspective"},
       {"perspective",
        {{"yfov", glm::radians(35.0f)}, {"aspectRatio", 1.0}, {"znear", 0.05}, {"zfar", 200.0}}}}};
  // At (0, 3, 11), pitched down 12 degrees: the three spheres, their shadows and the horizon.
  rootNodes.push_back(
      gltf.addNode({{"name", "camera"},
                    {"camera", 0},
                    {"translation", {0.0, 3.0, 11.0}},
                    {"rotation", quaternionJson(glm::angleAxis(glm::radians(-12.0f), glm::vec3(1, 0, 0)))}}));
  gltf.doc["scene"] = 0;
  gltf.doc["scenes"] = {{{"name", "sunlit_spheres"}, {"nodes", rootNodes}}};
  gltf.write(outDir, "sunlit_spheres");
  std::cout << "wrote " << (outDir / "sunlit_spheres.gltf").string() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path outDir = argc > 1 ? std::filesystem::path(argv[1]) : wb::assetDir();
  std::filesystem::create_directories(outDir);
  GltfWriter gltf;
  gltf.doc["extensionsUsed"] = {"KHR_materials_emissive_strength", "KHR_materials_specular",
                                "KHR_lights_punctual"};

  // Materials.
  const int white = gltf.addMaterial(lambertian("white_wall", glm::vec3(0.73f)));
  const int red = gltf.addMaterial(lambertian("red_wall", glm::vec3(0.63f, 0.065f, 0.05f)));
  const int green = gltf.addMaterial(lambertian("green_wall", glm::vec3(0.14f, 0.45f, 0.091f)));
  const int light = gltf.addMaterial(
      {{"name", "ceiling_light"},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.0, 0.0, 0.0, 1.0}}, {"metallicFactor", 0.0}}},
       {"emissiveFactor", {1.0, 0.85, 0.6}},
       {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 12.0}}}}}});
  const int roughWhite = gltf.addMaterial(pbr("rough_white_dielectric", glm::vec3(0.8f), 0.0f, 0.9f));
  json glossy = pbr("glossy_blue_dielectric", glm::vec3(0.1f, 0.25f, 0.7f), 0.0f, 0.15f);
  glossy["extensions"] = {
      {"KHR_materials_specular", {{"specularFactor", 1.0}, {"specularColorFactor", {0.9, 0.95, 1.0}}}}};
  const int glossyBlue = gltf.addMaterial(glossy);
  const int silver =
      gltf.addMaterial(pbr("polished_silver_metal", glm::vec3(0.97f, 0.96f, 0.91f), 1.0f, 0.05f));
  const int gold = gltf.addMaterial(pbr("rough_gold_metal", glm::vec3(1.0f, 0.766f, 0.336f), 1.0f, 0.45f));
  const int leaf = gltf.addMaterial(
      {{"name", "leaf_mask"},
       {"pbrMetallicRoughness",
        {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.0}, {"roughnessFactor", 0.6}}},
       {"alphaMode", "MASK"},
       {"alphaCutoff", 0.5},
       {"doubleSided", true}});

  // Leaf texture.
  constexpr int kLeafSize = 128;
  const std::vector<uint8_t> leafPixels = makeLeafImage(kLeafSize);
  if (!stbi_write_png((outDir / "default_scene_leaf.png").c_str(), kLeafSize, kLeafSize, 4, leafPixels.data(),
                      kLeafSize * 4)) {
    std::cerr << "cannot write " << (outDir / "default_scene_leaf.png") << "\n";
    return 1;
  }
  gltf.doc["images"] = {{{"uri", "default_scene_leaf.png"}, {"name", "leaf"}}};
  gltf.doc["samplers"] = {{{"magFilter", 9729}, {"minFilter", 9987}, {"wrapS", 33071}, {"wrapT", 33071}}};
  gltf.doc["textures"] = {{{"source", 0}, {"sampler", 0}}};

  // Room: x in [-1, 1], y in [0, 2], z in [-1, 1], open at z = +1; all faces point inwards.
  MeshData whiteWalls, redWall, greenWall, panel, leafQuad;
  addQuad(whiteWalls, {-1, 0, 1}, {2, 0, 0}, {0, 0, -2});               // floor, +Y
  addQuad(whiteWalls, {-1, 2, -1}, {2, 0, 0}, {0, 0, 2});               // ceiling, -Y
  addQuad(whiteWalls, {-1, 0, -1}, {2, 0, 0}, {0, 2, 0});               // back, +Z
  addQuad(redWall, {-1, 0, 1}, {0, 0, -2}, {0, 2, 0});                  // left, +X
  addQuad(greenWall, {1, 0, -1}, {0, 0, 2}, {0, 2, 0});                 // right, -X
  addQuad(panel, {-0.25f, 1.98f, -0.25f}, {0.5f, 0, 0}, {0, 0, 0.5f});  // emitter, facing down
  addQuad(leafQuad, {-0.3f, 0.05f, 0}, {0.6f, 0, 0}, {0, 0.9f, 0});     // leaf, facing +Z (double-sided)

  json roomPrimitives = json::array();
  for (auto [data, material] : {std::pair{&whiteWalls, white}, {&redWall, red}, {&greenWall, green}}) {
    json primitive = gltf.addMeshData(*data);
    primitive["material"] = material;
    roomPrimitives.push_back(primitive);
  }
  const int roomMesh = gltf.addMesh("cornell_room", roomPrimitives);
  json panelPrimitive = gltf.addMeshData(panel);
  panelPrimitive["material"] = light;
  const int panelMesh = gltf.addMesh("ceiling_light", json::array({panelPrimitive}));
  json leafPrimitive = gltf.addMeshData(leafQuad);
  leafPrimitive["material"] = leaf;
  const int leafMesh = gltf.addMesh("leaf", json::array({leafPrimitive}));

  // One unit sphere's accessors shared by four meshes that differ only in material.
  const json spherePrimitive = gltf.addMeshData(makeSphere(64, 32));
  struct SphereSpec {
    const char* name;
    int material;
    glm::vec3 centre;
    float radius;
  };
  const SphereSpec spheres[] = {{"sphere_rough_white", roughWhite, {-0.55f, 0.3f, -0.45f}, 0.3f},
                                {"sphere_glossy_blue", glossyBlue, {0.55f, 0.3f, -0.45f}, 0.3f},
                                {"sphere_polished_silver", silver, {-0.4f, 0.22f, 0.35f}, 0.22f},
                                {"sphere_rough_gold", gold, {0.4f, 0.22f, 0.3f}, 0.22f}};
  json rootNodes = json::array();
  rootNodes.push_back(gltf.addNode({{"name", "cornell_room"}, {"mesh", roomMesh}}));
  rootNodes.push_back(gltf.addNode({{"name", "ceiling_light"}, {"mesh", panelMesh}}));
  for (const SphereSpec& s : spheres) {
    json primitive = spherePrimitive;
    primitive["material"] = s.material;
    const int mesh = gltf.addMesh(s.name, json::array({primitive}));
    rootNodes.push_back(gltf.addNode({{"name", s.name},
                                      {"mesh", mesh},
                                      {"translation", {s.centre.x, s.centre.y, s.centre.z}},
                                      {"scale", {s.radius, s.radius, s.radius}}}));
  }
  // The leaf stands between the back spheres, turned 20 degrees about Y.
  rootNodes.push_back(
      gltf.addNode({{"name", "leaf"},
                    {"mesh", leafMesh},
                    {"translation", {0.0, 0.0, -0.6}},
                    {"rotation", quaternionJson(glm::angleAxis(glm::radians(20.0f), glm::vec3(0, 1, 0)))}}));

  // Sun: travels down and into the room through the open front, so the spheres' shadows fall on the floor.
  rootNodes.push_back(addSun(gltf, glm::vec3(-0.25f, -0.9f, -1.0f), {1.0, 0.96, 0.9}, 2.5));

  // Camera as in ../shared/reference/cornell.gltf: at (0, 1, 3.9) looking along -Z, 40 degree vertical fov.
  gltf.doc["cameras"] = {
      {{"name", "front"},
       {"type", "perspective"},
       {"perspective",
        {{"yfov", glm::radians(40.0f)}, {"aspectRatio", 1.0}, {"znear", 0.05}, {"zfar", 100.0}}}}};
  rootNodes.push_back(gltf.addNode({{"name", "camera"}, {"camera", 0}, {"translation", {0.0, 1.0, 3.9}}}));

  gltf.doc["scene"] = 0;
  gltf.doc["scenes"] = {{{"name", "default"}, {"nodes", rootNodes}}};
  gltf.write(outDir, "default_scene");
  std::cout << "wrote " << (outDir / "default_scene.gltf").string() << "\n";
  writeSunlitScene(outDir);
  return 0;
}
