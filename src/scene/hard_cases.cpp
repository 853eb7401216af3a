#include "scene/hard_cases.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include <stb/stb_image_write.h>

#include "common/atomic_file.h"
#include "scene/procedural.h"

namespace wb::scene {
namespace {

gpu::Vertex vertex(glm::vec3 p, glm::vec3 n, glm::vec2 uv, glm::vec4 t) {
  return makeVertex(p, n, uv, t);
}

gpu::Material material(glm::vec3 base, float metallic, float roughness, float specular) {
  return makeMaterial(base, metallic, roughness, specular);
}

gpu::Material whiteLambert() {
  return material(glm::vec3(1.0f), 0.0f, 1.0f, 0.0f);
}

Primitive quad(float h, int mat) {
  return makeQuad(h, mat).primitives[0];
}

Primitive sphere(float r, int mat, int segments = 48, int rings = 24) {
  return makeUvSphere(r, mat, segments, rings).primitives[0];
}

Scene oneMesh(const std::string& name, std::vector<gpu::Material> materials, std::vector<Primitive> prims,
              glm::vec3 eye, glm::vec3 target, float yfov, float radius) {
  Scene sc;
  sc.sourcePath = name;
  sc.materials = std::move(materials);
  for (size_t i = 0; i < sc.materials.size(); ++i)
    sc.materialNames.push_back(std::string("m").append(std::to_string(i)));
  Mesh mesh;
  mesh.name = name;
  mesh.primitives = std::move(prims);
  sc.meshes = {mesh};
  sc.instances.push_back({0, glm::mat4(1.0f), name});
  sc.camera.eye = eye;
  sc.camera.target = target;
  sc.camera.up = glm::vec3(0, 1, 0);
  sc.camera.yfov = yfov;
  sc.camera.znear = radius * 1e-3f;
  sc.bounds = {glm::vec3(-radius), glm::vec3(radius)};
  return sc;
}

// A uniform environment of radiance 0.5 with one pixel of a 64x32 map carrying `peak` (a tiny, very bright
// sun), written once as a Radiance .hdr in the temporary folder.
std::string tinySunEnvironment(float peak) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("wb_hard_case_tiny_sun_" + std::to_string(::getpid()) + ".hdr");
  const int w = 64, h = 32;
  std::vector<float> rgb(size_t(w) * h * 3, 0.5f);
  const size_t sun = (size_t(8) * w + 20) * 3;
  rgb[sun] = rgb[sun + 1] = rgb[sun + 2] = peak;
  std::string hdr;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
  };
  if (!stbi_write_hdr_to_func(append, &hdr, w, h, 3, rgb.data()))
    throw std::runtime_error("cannot encode " + path.string());
  writeFileAtomically(path, hdr, "hard case environment");
  return path.string();
}

// A white furnace's environment: uniform radiance 1, no map. A furnace only converges to 1 without a short
// bounce cap.
void furnace(HardCase& c) {
  c.settings = {"env=", "env_color=1,1,1", "env_intensity=1"};
  c.minBounces = 64;
}

}  // namespace

std::vector<HardCase> hardCases() {
  std::vector<HardCase> cases;
  const std::vector<std::string> samplingVariants = {"", "--no-nee", "--no-mis"};

  {  // Grazing incidence: a white Lambert plane seen edge-on; the upper hemisphere is unoccluded: value 1.
    HardCase c;
    c.name = "grazing-lambert";
    c.risk = "grazing incidence (camera 0.5 deg above a plane)";
    c.scene = oneMesh(c.name, {whiteLambert()}, {quad(1000.0f, 0)}, {0, 0.05f, 0},
                      {0, 0.05f - 0.0087f * 6, -6}, 0.3f, 1000.0f);
    c.variants = samplingVariants;
    furnace(c);
    c.furnaceValue = 1.0;
    cases.push_back(std::move(c));
  }
  {  // Grazing on a smooth metal plane: the specular lobe at grazing angles (energy loss expected, not 1).
    HardCase c;
    c.name = "grazing-metal";
    c.risk = "grazing incidence on a smooth metal (roughness 0.05)";
    c.scene = oneMesh(c.name, {material(glm::vec3(1.0f), 1.0f, 0.05f, 1.0f)}, {quad(1000.0f, 0)},
                      {0, 0.05f, 0}, {0, 0.05f - 0.0087f * 6, -6}, 0.3f, 1000.0f);
    c.variants = samplingVariants;
    furnace(c);
    cases.push_back(std::move(c));
  }
  // Roughness 0 and 1 on metals and dielectrics: spheres in the white furnace.
  struct Rough {
    const char* name;
    const char* risk;
    float metallic, roughness, specular;
  };
  for (const Rough& r : {Rough{"metal-rough0", "white metal, roughness 0", 1, 0, 1},
                         Rough{"metal-rough1", "white metal, roughness 1", 1, 1, 1},
                         Rough{"dielectric-rough0", "white base + specular layer, roughness 0", 0, 0, 1},
                         Rough{"dielectric-rough1", "white base + specular layer, roughness 1", 0, 1, 1}}) {
    HardCase c;
    c.name = r.name;
    c.risk = r.risk;
    c.scene = oneMesh(c.name, {material(glm::vec3(1.0f), r.metallic, r.roughness, r.specular)},
                      {sphere(1.0f, 0)}, {0, 0, 2.2f}, {0, 0, 0}, 0.8f, 1.0f);
    c.variants = samplingVariants;
    furnace(c);
    c.furnaceValue = 1.0;  // the ideal; single-scattering microfacet models lose some energy at roughness 1
    c.note =
        "`--no-mis` samples the environment by light sampling only: a (near-)delta specular lobe cannot be "
        "reached that way, so it goes black or very noisy by design. Single-scattering microfacet models "
        "lose "
        "energy at high roughness; a value above 1 is energy creation.";
    cases.push_back(std::move(c));
  }
  {  // Tiny, very bright sun in an HDR environment (importance sampling must find one texel).
    HardCase c;
    c.name = "tiny-sun-hdr";
    c.risk = "one 64x32 env texel at 5e4 (others 0.5), a Lambert sphere on a plane";
    auto sc = oneMesh(c.name, {material(glm::vec3(0.8f), 0, 1, 0)}, {sphere(1.0f, 0), quad(20.0f, 0)},
                      {0, 1.5f, 4.0f}, {0, 0, 0}, 0.8f, 20.0f);
    sc.meshes[0].primitives[1].vertices[0].position.y = -1;  // the plane under the sphere
    for (auto& v : sc.meshes[0].primitives[1].vertices) v.position.y = -1.0f;
    c.scene = sc;
    c.variants = samplingVariants;
    const std::string env = tinySunEnvironment(5.0e4f);
    c.settings = {"env=" + env, "env_intensity=1"};
    cases.push_back(std::move(c));
  }
  for (float scale : {1e-3f, 1e5f}) {  // Extreme scales: the furnace sphere at 1 mm and 100 km.
    HardCase c;
    c.name = scale < 1 ? "scale-1e-3" : "scale-1e5";
    c.risk = "white Lambert sphere of radius " + std::string(scale < 1 ? "1e-3" : "1e5") + " (ray epsilons)";
    c.scene = oneMesh(c.name, {whiteLambert()}, {sphere(scale, 0)}, glm::vec3(0, 0, 2.2f * scale), {0, 0, 0},
                      0.8f, scale);
    c.variants = samplingVariants;
    furnace(c);
    c.furnaceValue = 1.0;
    cases.push_back(std::move(c));
  }
  {  // Degenerate triangles: zero-area (repeated vertex, collinear) and needle triangles inside a closed
     // sphere.
    HardCase c;
    c.name = "degenerate-triangles";
    c.risk = "zero-area, collinear and needle triangles added to a furnace sphere";
    auto p = sphere(1.0f, 0);
    const uint32_t n = uint32_t(p.vertices.size());
    const glm::vec4 t(1, 0, 0, 1);
    p.vertices.push_back(vertex({0.3f, 0.2f, 0.999f}, {0, 0, 1}, {0, 0}, t));
    p.vertices.push_back(vertex({0.3f + 1e-7f, 0.2f, 0.999f}, {0, 0, 1}, {0, 0}, t));
    p.vertices.push_back(vertex({-0.5f, -0.5f, 0.8f}, {0, 0, 1}, {0, 0}, t));
    p.vertices.push_back(vertex({0.5f, 0.5f, 0.8f}, {0, 0, 1}, {0, 0}, t));
    p.vertices.push_back(vertex({0.0f, 0.0f, 0.8f}, {0, 0, 1}, {0, 0}, t));  // collinear with the two above
    for (uint32_t i = 0; i < 6; ++i) p.indices.insert(p.indices.end(), {0u + i, 0u + i, 1u + i});  // repeated
    p.indices.insert(p.indices.end(), {n, n + 1, n});          // zero area
    p.indices.insert(p.indices.end(), {n + 2, n + 3, n + 4});  // collinear
    // Needles: full-height slivers 1e-6 wide across the front of the sphere.
    for (int k = 0; k < 8; ++k) {
      const float x = -0.6f + 0.15f * float(k);
      const uint32_t b = uint32_t(p.vertices.size());
      p.vertices.push_back(vertex({x, -0.6f, 0.6f}, {0, 0, 1}, {0, 0}, t));
      p.vertices.push_back(vertex({x + 1e-6f, 0.6f, 0.6f}, {0, 0, 1}, {0, 0}, t));
      p.vertices.push_back(vertex({x, 0.6f, 0.6f}, {0, 0, 1}, {0, 0}, t));
      p.indices.insert(p.indices.end(), {b, b + 1, b + 2});
    }
    c.scene = oneMesh(c.name, {whiteLambert()}, {p}, {0, 0, 2.2f}, {0, 0, 0}, 0.8f, 1.0f);
    c.variants = samplingVariants;
    furnace(c);
    c.furnaceValue = 1.0;  // the slivers are inside the sphere: hidden
    cases.push_back(std::move(c));
  }
  {  // Broken tangents and normals: zero, NaN and non-unit tangents, zero normals, on a normal-mapped sphere.
    HardCase c;
    c.name = "broken-tangents";
    c.risk = "zero/NaN/huge tangents and zero normals on a white furnace sphere";
    auto p = sphere(1.0f, 0);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (size_t i = 0; i < p.vertices.size(); ++i) {
      auto& v = p.vertices[i];
      switch (i % 5) {
        case 0:
          v.tangent = glm::vec4(0.0f);
          break;
        case 1:
          v.tangent = glm::vec4(nan, nan, nan, 1.0f);
          break;
        case 2:
          v.tangent = glm::vec4(1e20f, 0, 0, 1);
          break;
        case 3:
          v.normal = glm::vec3(0.0f);
          break;
        default:
          v.tangent = glm::vec4(v.normal, 1.0f);
          break;  // parallel to the normal
      }
    }
    c.scene = oneMesh(c.name, {whiteLambert()}, {p}, {0, 0, 2.2f}, {0, 0, 0}, 0.8f, 1.0f);
    // A flat normal map (128, 128, 255) so the tangent frame is used.
    Image img;
    img.name = "flat-normal";
    img.width = img.height = 4;
    for (int k = 0; k < 16; ++k) img.rgba8.insert(img.rgba8.end(), {128, 128, 255, 255});
    c.scene.images.push_back(img);
    c.scene.textures.push_back({0, -1});
    c.scene.textureIsSrgb.push_back(false);
    c.scene.materials[0].normalTexture = 0;
    c.variants = samplingVariants;
    furnace(c);
    c.furnaceValue = 1.0;
    cases.push_back(std::move(c));
  }
  {  // Long specular chains: the camera between two parallel white mirrors (F0 = 1): radiance 1 after many
     // bounces.
    HardCase c;
    c.name = "mirror-corridor";
    c.risk = "long specular chains (two parallel perfect mirrors, 256 bounces)";
    auto a = quad(50.0f, 0), b = quad(50.0f, 0);
    for (auto& v : a.vertices) v.position.y = -0.5f;
    for (auto& v : b.vertices) {
      v.position.y = 0.5f;
      v.normal = glm::vec3(0, -1, 0);
    }
    b.indices = {0, 1, 2, 0, 2, 3};  // facing down
    c.scene = oneMesh(c.name, {material(glm::vec3(1.0f), 1.0f, 0.0f, 1.0f)}, {a, b}, {0, 0, 0},
                      {0, -0.3f, -1}, 0.9f, 50.0f);
    c.variants = {"", "--no-rr"};
    furnace(c);
    c.settings.push_back("max_bounces=256");
    c.furnaceValue = 1.0;
    c.note = "paths that run out of bounces are black";
    cases.push_back(std::move(c));
  }
  {  // Alpha-masked foliage: 24 stacked double-sided white Lambert leaves with a checker alpha mask.
    HardCase c;
    c.name = "alpha-foliage";
    c.risk = "24 layers of alpha-masked (checker) double-sided white leaves";
    auto m = whiteLambert();
    m.alphaMode = WB_ALPHA_MASK;
    m.flags = WB_MATERIAL_DOUBLE_SIDED;
    m.baseColorTexture = 0;
    std::vector<Primitive> prims;
    for (int k = 0; k < 24; ++k) {
      auto q = quad(1.0f, 0);
      for (auto& v : q.vertices) {
        v.position = glm::vec3(v.position.x + 0.05f * float(k % 3), v.position.z, -0.1f * float(k));
        v.normal = glm::vec3(0, 0, 1);  // the winding below makes the geometric normal +Z too
        v.u *= 4.0f + float(k % 5);
        v.v *= 4.0f + float(k % 7);
      }
      q.indices = {0, 1, 2, 0, 2, 3};
      prims.push_back(q);
    }
    c.scene = oneMesh(c.name, {m}, prims, {0, 0, 3.0f}, {0, 0, -1}, 0.7f, 3.0f);
    Image img;
    img.name = "checker-alpha";
    img.width = img.height = 8;
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        img.rgba8.insert(img.rgba8.end(), {255, 255, 255, uint8_t(((x + y) % 2) ? 255 : 0)});
    c.scene.images.push_back(img);
    c.scene.samplers.push_back({9728, 9728, 10497, 10497});
    c.scene.textures.push_back({0, 0});
    c.scene.textureIsSrgb.push_back(true);
    c.variants = samplingVariants;
    furnace(c);
    c.furnaceValue = 1.0;
    // Control: the same leaves opaque and untextured (isolates the alpha mask from the stacked geometry).
    HardCase control;
    control.name = "opaque-leaves-control";
    control.risk = "the foliage stack, opaque and untextured";
    control.scene = c.scene;
    control.scene.materials[0].alphaMode = WB_ALPHA_OPAQUE;
    control.scene.materials[0].baseColorTexture = -1;
    control.variants = {""};
    furnace(control);
    control.furnaceValue = 1.0;
    cases.push_back(std::move(c));
    cases.push_back(std::move(control));
  }
  return cases;
}

}  // namespace wb::scene
