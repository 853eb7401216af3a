// What every stage of glTF conversion shares: the parsed model, the file name for messages and the warnings.
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/scene.h"

namespace wb::scene {

class LoadContext {
 public:
  LoadContext(const tinygltf::Model& model, std::string fileName, std::vector<std::string>& warnings)
      : model_(model), fileName_(std::move(fileName)), warnings_(warnings) {}

  const tinygltf::Model& model() const { return model_; }
  const std::string& fileName() const { return fileName_; }

  // Throws SceneError "<file>: <reason>".
  [[noreturn]] void fail(const std::string& reason) const;
  // Adds a warning once (identical warnings are not repeated).
  void warn(const std::string& warning);

 private:
  const tinygltf::Model& model_;
  std::string fileName_;
  std::vector<std::string>& warnings_;
};

// Replaces line breaks with "; " so a message stays on one line.
std::string oneLine(const std::string& text);

}  // namespace wb::scene
