// Builds small glTF files inside tests: one buffer embedded as a base64 data URI, JSON editable directly.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace wb::scene::test {

constexpr int kByte = 5120, kUByte = 5121, kShort = 5122, kUShort = 5123, kUInt = 5125, kFloat = 5126;

class SyntheticGltf {
 public:
  SyntheticGltf();

  nlohmann::json json;  // asset/scenes/nodes/meshes/... (buffers are filled in by write())

  // Appends bytes (4-byte aligned) as a new bufferView; returns its index.
  int addBufferView(const std::vector<uint8_t>& bytes, int byteStride = 0);
  int addAccessor(int bufferView, int componentType, size_t count, const std::string& type,
                  bool normalized = false, size_t byteOffset = 0);
  template <class T>
  int addData(const std::vector<T>& values, int componentType, const std::string& type,
              bool normalized = false) {
    std::vector<uint8_t> bytes(values.size() * sizeof(T));
    if (!bytes.empty()) std::memcpy(bytes.data(), values.data(), bytes.size());
    const size_t components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
    return addAccessor(addBufferView(bytes), componentType, values.size() / components, type, normalized);
  }

  // One node (index 0, in scene 0) with one mesh (index 0) of one triangle primitive; returns the primitive.
  nlohmann::json& addSingleMeshNode(const nlohmann::json& primitive);

  // Writes <tempdir>/wb_scene_tests/<name>.gltf and returns its path.
  std::filesystem::path write(const std::string& name) const;

 private:
  std::vector<uint8_t> buffer_;
};

std::string base64(const std::vector<uint8_t>& bytes);
std::filesystem::path writeTextFile(const std::string& name, const std::string& text);
std::filesystem::path writeBinaryFile(const std::string& name, const std::vector<uint8_t>& bytes);

}  // namespace wb::scene::test
