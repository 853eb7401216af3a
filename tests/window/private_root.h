#pragma once
// A private copy of the project's shaders/ and assets/ in dir/root: the window's WB_ROOT for a test that
// edits shaders as a user would.
#include <filesystem>

namespace wb::testing {

inline std::filesystem::path privateRoot(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  const fs::path root = dir / "root";
  fs::create_directories(root);
  fs::copy(fs::path(WB_SOURCE_DIR) / "shaders", root / "shaders", fs::copy_options::recursive);
  fs::copy(fs::path(WB_SOURCE_DIR) / "assets", root / "assets", fs::copy_options::recursive);
  return root;
}

}  // namespace wb::testing
