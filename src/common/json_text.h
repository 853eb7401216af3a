// JSON text for every file and line the workbench writes. File names, shader sources and compiler messages
// are arbitrary bytes; nlohmann::json throws (type_error.316) on a string that is not UTF-8 unless told
// otherwise: here invalid bytes become U+FFFD.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

namespace wb {

inline std::string jsonText(const nlohmann::json& j, int indent = -1) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace wb
