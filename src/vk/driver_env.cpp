#include "vk/driver_env.h"

#include <cctype>
#include <cstdlib>

namespace wb::vk {
namespace {

bool isSet(const char* name) {
  const char* v = std::getenv(name);
  return v && *v;
}

}  // namespace

std::vector<std::string> applyDriverDefaults(const std::filesystem::path& cacheDir) {
  static const std::vector<std::string> applied = [&] {
    std::vector<std::string> set;
    auto setDefault = [&](const char* name, const std::string& value) {
      ::setenv(name, value.c_str(), 1);  // unset or empty: ours to set
      set.push_back(std::string(name) + "=" + value);
    };
    const bool usersCache = isSet("MESA_SHADER_CACHE_DIR");
    if (!isSet("LP_NATIVE_VECTOR_WIDTH") && !usersCache) setDefault("LP_NATIVE_VECTOR_WIDTH", "128");
    if (!usersCache) {  // the width is set by now: the user's or ours
      std::string folder = "lp";
      for (const char* c = std::getenv("LP_NATIVE_VECTOR_WIDTH"); *c; ++c)
        folder += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
      setDefault("MESA_SHADER_CACHE_DIR", (cacheDir / "mesa" / folder).string());
    }
    return set;
  }();
  return applied;
}

}  // namespace wb::vk
