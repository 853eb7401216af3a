#include "synthetic_gltf.h"

#include <fstream>

namespace wb::scene::test {
namespace {

std::filesystem::path testDir() {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "wb_scene_tests";
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace

SyntheticGltf::SyntheticGltf() {
  json["asset"] = {{"version", "2.0"}};
  json["bufferViews"] = nlohmann::json::array();
  json["accessors"] = nlohmann::json::array();
}

int SyntheticGltf::addBufferView(const std::vector<uint8_t>& bytes, int byteStride) {
  while (buffer_.size() % 4 != 0) buffer_.push_back(0);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", buffer_.size()}, {"byteLength", bytes.size()}};
  if (byteStride) view["byteStride"] = byteStride;
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  json["bufferViews"].push_back(view);
  return static_cast<int>(json["bufferViews"].size() - 1);
}

int SyntheticGltf::addAccessor(int bufferView, int componentType, size_t count, const std::string& type,
                               bool normalized, size_t byteOffset) {
  nlohmann::json accessor = {
      {"bufferView", bufferView}, {"componentType", componentType}, {"count", count}, {"type", type}};
  if (normalized) accessor["normalized"] = true;
  if (byteOffset) accessor["byteOffset"] = byteOffset;
  json["accessors"].push_back(accessor);
  return static_cast<int>(json["accessors"].size() - 1);
}

nlohmann::json& SyntheticGltf::addSingleMeshNode(const nlohmann::json& primitive) {
  json["scene"] = 0;
  json["scenes"] = {{{"nodes", {0}}}};
  json["nodes"] = {{{"mesh", 0}, {"name", "triangle"}}};
  json["meshes"] = {{{"primitives", {primitive}}}};
  return json["meshes"][0]["primitives"][0];
}

std::filesystem::path SyntheticGltf::write(const std::string& name) const {
  nlohmann::json out = json;
  if (!buffer_.empty()) {
    out["buffers"] = {
        {{"byteLength", buffer_.size()}, {"uri", "data:application/octet-stream;base64," + base64(buffer_)}}};
  }
  return writeTextFile(name + ".gltf", out.dump(1));
}

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], table[v & 63]};
  }
  if (i + 1 == bytes.size()) {
    const uint32_t v = uint32_t(bytes[i]) << 16;
    out += {table[v >> 18], table[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8);
    out += {table[v >> 18], table[(v >> 12) & 63], table[(v >> 6) & 63], '='};
  }
  return out;
}

std::filesystem::path writeTextFile(const std::string& name, const std::string& text) {
  const std::filesystem::path path = testDir() / name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::filesystem::path writeBinaryFile(const std::string& name, const std::vector<uint8_t>& bytes) {
  const std::filesystem::path path = testDir() / name;
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  return path;
}

}  // namespace wb::scene::test
