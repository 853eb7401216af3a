// JSON text for every file and line the workbench writes. File names, shader sources and compiler messages
// are arbitrary bytes; nlohmann::json throws (type_error.316) on a string that is not UTF-8 unless told
// otherwise: here invalid bytes become U+FFFD.
#pragma once
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "common/atomic_file.h"

namespace wb {

inline std::string jsonText(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A JSON file (indented, one trailing newline), written whole or not at all (common/atomic_file.h); throws
// std::runtime_error naming `what` and the path.
inline void writeJsonFile(const std::filesystem::path& path, const nlohmann::json& j,
                          const std::string& what) {
  writeFileAtomically(path, jsonText(j, 2) + "\n", what);
}

}  // namespace wb
