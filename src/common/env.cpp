#include "common/env.h"

#include <cstdlib>

namespace wb::env {

std::optional<std::string> get(const char* name) {
  const char* v = std::getenv(name);
  if (!v || !*v) return std::nullopt;
  return std::string(v);
}

std::optional<bool> choice(const char* name) {
  const auto v = get(name);
  if (v == "1") return true;
  if (v == "0") return false;
  return std::nullopt;
}

bool enabled(const char* name) {
  const auto v = get(name);
  return v && *v != "0";
}

std::optional<double> number(const char* name) {
  const auto v = get(name);
  if (!v) return std::nullopt;
  char* end = nullptr;
  const double d = std::strtod(v->c_str(), &end);
  if (end == v->c_str() || *end != '\0') return std::nullopt;
  return d;
}

void set(const char* name, const std::string& value) {
  ::setenv(name, value.c_str(), 1);
}

}  // namespace wb::env
