// Every file under ../shared/assets/gltf-malformed is either refused with a one-line SceneError or, where the
// damage can be repaired safely, loaded (each such case justified below). Never a crash.
#include <gtest/gtest.h>

#include <map>

#include "common/paths.h"
#include "scene/scene.h"
#include "synthetic_gltf.h"

namespace wb::scene {
namespace {

struct Outcome {
  bool loads;
  std::string messagePart;  // refused: part of the SceneError message; loads: part of a warning
};

// Relative path -> expected outcome.
const std::map<std::string, Outcome> kExpected = {
    // NORMAL holds zero/non-unit vectors; positions and indices are fine, so the loader regenerates
    // area-weighted normals (with a warning) instead of refusing a perfectly renderable box.
    {"assimp/BoxBadNormals-glTF-Binary/BoxBadNormals.glb", {true, "normals regenerated"}},
    {"assimp/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", {false, "NaN or infinite"}},
    {"assimp/IndexOutOfRange/AllIndicesOutOfRange.gltf", {false, "out of range"}},
    {"assimp/IndexOutOfRange/IndexOutOfRange.gltf", {false, "out of range"}},
    {"assimp/MissingBin/BoxTextured.gltf", {false, "BoxTextured0.bin"}},
    {"assimp/RecursiveNodes/RecursiveNodes.gltf", {false, "cycle"}},
    // These four are caught by tinygltf's own parser already (its message is passed on).
    {"tinygltf/BoundsChecking/integer-out-of-bounds.gltf", {false, "byteLength"}},
    {"tinygltf/BoundsChecking/invalid-buffer-index.gltf", {false, "buffer \"1\" not found"}},
    {"tinygltf/BoundsChecking/invalid-buffer-view-index.gltf", {false, "invalid bufferView"}},
    {"tinygltf/BoundsChecking/invalid-primitive-indices.gltf", {false, "indices accessor out of bounds"}},
    // A skin whose "skeleton" key is misspelt ("0skeleton") plus animations: valid geometry; skins and
    // animations are unsupported and only named in warnings (the mesh is shown in its bind pose).
    {"tinygltf/regression/unassigned-skeleton.gltf", {true, "skin"}},
    // Despite its name the container is consistent: JSON chunk 664 bytes, BIN chunk 44 bytes = buffer 0's
    // byteLength, accessors inside their views (tinygltf issue 440 was a crash in its own GLB reader). It is
    // a
    // valid one-triangle scene, so it loads. Truly zero-sized chunks are refused
    // (BadInput.BrokenGlbContainers).
    {"tinygltf/regression/zero-sized-bin-chunk-issue-440.glb", {true, ""}},
};

TEST(MalformedAssets, EveryFileIsRefusedOrLoadedSafely) {
  const std::filesystem::path root = wb::sharedDir() / "assets" / "gltf-malformed";
  ASSERT_TRUE(std::filesystem::is_directory(root)) << root;
  size_t checked = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const std::string extension = entry.path().extension().string();
    if (!entry.is_regular_file() || (extension != ".gltf" && extension != ".glb")) continue;
    const std::string relative = std::filesystem::relative(entry.path(), root).generic_string();
    SCOPED_TRACE(relative);
    const auto expected = kExpected.find(relative);
    ASSERT_NE(expected, kExpected.end()) << "new malformed file without an expected outcome: " << relative;
    ++checked;
    if (expected->second.loads) {
      Scene scene;
      ASSERT_NO_THROW(scene = loadGltf(entry.path()));
      EXPECT_GT(scene.triangleCount(), 0u);
      bool warned = expected->second.messagePart.empty();
      for (const std::string& w : scene.warnings)
        warned |= w.find(expected->second.messagePart) != std::string::npos;
      EXPECT_TRUE(warned) << "expected a warning containing '" << expected->second.messagePart << "'";
    } else {
      try {
        loadGltf(entry.path());
        ADD_FAILURE() << "loaded, expected SceneError";
      } catch (const SceneError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(entry.path().filename().string()), std::string::npos) << message;
        EXPECT_NE(message.find(expected->second.messagePart), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      }
    }
  }
  EXPECT_EQ(checked, kExpected.size());
}

TEST(MalformedAssets, BadNormalsAreRegeneratedAsUnitVectors) {
  const Scene scene =
      loadGltf(wb::sharedDir() / "assets/gltf-malformed/assimp/BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  const Primitive& primitive = scene.meshes.at(0).primitives.at(0);
  EXPECT_TRUE(primitive.generatedNormals);
  for (const gpu::Vertex& v : primitive.vertices) EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-5f);
}

void expectRefused(const std::filesystem::path& path, const std::string& part) {
  try {
    loadGltf(path);
    ADD_FAILURE() << path << " loaded, expected SceneError";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(BadInput, MissingFileEmptyFileAndGarbage) {
  expectRefused("/nonexistent/dir/scene.gltf", "file not found");
  expectRefused(test::writeTextFile("empty.gltf", ""), "empty");
  expectRefused(test::writeTextFile("garbage.gltf", "this is not json"), "garbage.gltf");
  expectRefused(test::writeTextFile("truncated.gltf", "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": ["),
                "truncated.gltf");
  expectRefused(std::filesystem::temp_directory_path(), "directory");
}

std::vector<uint8_t> glbHeader(uint32_t totalLength) {
  std::vector<uint8_t> bytes = {'g', 'l', 'T', 'F', 2, 0, 0, 0};
  for (int i = 0; i < 4; ++i) bytes.push_back(uint8_t(totalLength >> (8 * i)));
  return bytes;
}

void appendU32(std::vector<uint8_t>& bytes, uint32_t value) {
  for (int i = 0; i < 4; ++i) bytes.push_back(uint8_t(value >> (8 * i)));
}

// An embedded image whose bufferView claims more bytes than its buffer holds: refused before the image
// decoder reads past the buffer (tinygltf itself does not check it).
TEST(BadInput, ImageBufferViewPastItsBuffer) {
  test::SyntheticGltf g;
  const std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  const int view = g.addBufferView(png);
  g.addSingleMeshNode({});
  g.json["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
  g.json["bufferViews"][view]["byteLength"] = 1 << 20;
  g.json["bufferViews"][view]["byteOffset"] = 0;
  expectRefused(g.write("image_view_overrun"), "runs past the end of its buffer");
  g.json["bufferViews"][view]["byteLength"] = 8;
  g.json["bufferViews"][view]["byteOffset"] = 1 << 30;
  expectRefused(g.write("image_view_offset"), "runs past the end of its buffer");
}

TEST(BadInput, BrokenGlbContainers) {
  expectRefused(test::writeBinaryFile("short.glb", {'g', 'l', 'T', 'F', 2, 0}), "shorter");
  {
    std::vector<uint8_t> bytes = glbHeader(1000);  // claims more than the file holds
    appendU32(bytes, 4);
    appendU32(bytes, 0x4E4F534A);
    bytes.insert(bytes.end(), {'{', '}', ' ', ' '});
    expectRefused(test::writeBinaryFile("length.glb", bytes), "exceeds file size");
  }
  {
    std::vector<uint8_t> bytes = glbHeader(12 + 8 + 4);
    appendU32(bytes, 400);  // chunk longer than the file
    appendU32(bytes, 0x4E4F534A);
    bytes.insert(bytes.end(), {'{', '}', ' ', ' '});
    expectRefused(test::writeBinaryFile("chunk.glb", bytes), "runs past the end");
  }
  {
    const std::string json = "{\"asset\":{\"version\":\"2.0\"}}  ";  // 30 bytes -> pad to 32
    std::vector<uint8_t> bytes = glbHeader(12 + 8 + 32 + 8);
    appendU32(bytes, 32);
    appendU32(bytes, 0x4E4F534A);
    bytes.insert(bytes.end(), json.begin(), json.end());
    while (bytes.size() < 12 + 8 + 32) bytes.push_back(' ');
    appendU32(bytes, 0);  // zero-sized BIN chunk
    appendU32(bytes, 0x004E4942);
    expectRefused(test::writeBinaryFile("zero_bin.glb", bytes), "zero-sized GLB chunk");
  }
}

}  // namespace
}  // namespace wb::scene
