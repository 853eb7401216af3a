#include "common/paths.h"

#include <stdexcept>
#include <system_error>

#include "common/env.h"

namespace fs = std::filesystem;

namespace wb {
namespace {

bool looksLikeRoot(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p / "shaders", ec) && fs::is_directory(p / "assets", ec);
}

fs::path findRoot() {
  if (const auto root = env::get("WB_ROOT")) {
    if (!looksLikeRoot(*root)) {
      throw std::invalid_argument("WB_ROOT=" + *root +
                                  ": not the workbench's folder (it needs shaders/ and assets/ in it)");
    }
    return fs::path(*root);
  }
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (fs::path p = exe.parent_path(); !p.empty() && p != p.root_path(); p = p.parent_path()) {
      if (looksLikeRoot(p)) return p;
    }
  }
  return fs::path(WB_SOURCE_DIR);
}

}  // namespace

fs::path projectRoot() {
  static const fs::path root = findRoot();
  return root;
}
fs::path shaderDir() {
  return projectRoot() / "shaders";
}
fs::path assetDir() {
  return projectRoot() / "assets";
}
fs::path shaderCacheDir() {
  if (const auto dir = env::get("WB_SHADER_CACHE_DIR")) return fs::path(*dir);
  return projectRoot() / "shader_cache";
}
fs::path sharedDir() {
  if (const auto dir = env::get("WB_SHARED_DIR")) return fs::path(*dir);
  return projectRoot().parent_path() / "shared";
}
fs::path defaultScenePath() {
  return assetDir() / "default_scene.gltf";
}

}  // namespace wb
