#include "common/paths.h"

#include <cstdlib>
#include <system_error>

namespace fs = std::filesystem;

namespace wb {
namespace {

bool looksLikeRoot(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p / "shaders", ec) && fs::is_directory(p / "assets", ec);
}

fs::path findRoot() {
  if (const char* env = std::getenv("WB_ROOT"); env && *env) return fs::path(env);
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
  if (const char* env = std::getenv("WB_SHADER_CACHE_DIR"); env && *env) return fs::path(env);
  return projectRoot() / "shader_cache";
}
fs::path sharedDir() {
  if (const char* env = std::getenv("WB_SHARED_DIR"); env && *env) return fs::path(env);
  return projectRoot().parent_path() / "shared";
}
fs::path defaultScenePath() {
  return assetDir() / "default_scene.gltf";
}

}  // namespace wb
