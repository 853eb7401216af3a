// Reads a .gltf/.glb file into a tinygltf::Model: checks the GLB container itself before tinygltf sees it and
// decodes every image to RGBA8 (an image that cannot be decoded becomes a warning, not a failure).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace wb::scene {

// Throws SceneError (naming the file) when the file is missing, unreadable or not parseable glTF.
tinygltf::Model parseGltfFile(const std::filesystem::path& path, std::vector<std::string>& warnings);

}  // namespace wb::scene
