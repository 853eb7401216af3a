// Folders of a test program's own under the temporary directory: <tmp>/<program>_<pid>/<name>, made empty on
// request and removed, with everything in them, when the program ends.
#pragma once
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace wb::testing {

// `name` under the program's folder (`program`: e.g. "wb_faults"), emptied and created.
inline std::filesystem::path tempFolder(const std::string& program, const std::string& name) {
  struct Root {
    std::filesystem::path path;
    ~Root() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Root root{std::filesystem::temp_directory_path() /
                         (program + "_" + std::to_string(::getpid()))};
  const std::filesystem::path d = root.path / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace wb::testing
