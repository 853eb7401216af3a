#include "app/parameter_json.h"

namespace wb::app {

nlohmann::json parametersJson(const render::Parameters& values) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& p : render::parameterList()) {
    const render::ParameterValue v = p.get(values);
    if (const bool* b = std::get_if<bool>(&v)) {
      j[p.name] = *b;
    } else if (const uint32_t* u = std::get_if<uint32_t>(&v)) {
      j[p.name] = *u;
    } else if (const float* f = std::get_if<float>(&v)) {
      j[p.name] = *f;
    } else if (const glm::vec3* c = std::get_if<glm::vec3>(&v)) {
      j[p.name] = {c->x, c->y, c->z};
    } else {
      j[p.name] = std::get<std::string>(v);
    }
  }
  return j;
}

}  // namespace wb::app
