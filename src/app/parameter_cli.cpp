#include "app/parameter_cli.h"

#include <cstdio>
#include <stdexcept>

namespace wb::app {
namespace {

std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string helpText(const render::ParameterInfo& p, const render::Parameters& defaults) {
  std::string h = p.help;
  switch (p.type) {
    case render::ParameterType::UInt:
    case render::ParameterType::Float: {
      const render::ParameterValue v = p.get(defaults);
      const double d =
          p.type == render::ParameterType::UInt ? double(std::get<uint32_t>(v)) : std::get<float>(v);
      h += " (default " + shortNumber(d) + "; " + shortNumber(p.min) + " .. " +
           (p.max < 1e30 ? shortNumber(p.max) : std::string("any")) + ")";
      break;
    }
    case render::ParameterType::Choice: {
      std::string c;
      for (const auto& x : p.choices) c += (c.empty() ? "" : "|") + x;
      h += " (" + c + "; default " + render::formatParameter(p, defaults) + ")";
      break;
    }
    default:
      break;
  }
  return h;
}

}  // namespace

void ParameterFlags::addTo(CLI::App& app, const render::Parameters& defaults) {
  for (const auto& p : render::parameterList()) {
    if (p.flag.empty()) continue;
    Flag& f = flags_.emplace_back();
    f.info = &p;
    if (p.type == render::ParameterType::Bool) {
      f.option = app.add_flag(p.flag, f.present, p.help);
    } else {
      f.option = app.add_option(p.flag, f.text, helpText(p, defaults));
    }
  }
}

void ParameterFlags::apply(render::Parameters& values) const {
  for (const auto& f : flags_) {
    if (f.option->count() == 0) continue;
    try {
      if (f.info->type == render::ParameterType::Bool) {
        f.info->put(values, f.info->flagSets);
      } else {
        f.info->put(values, render::parseParameter(*f.info, f.text));
      }
    } catch (const std::invalid_argument& e) {
      // The registry names the parameter; the user typed the flag.
      std::string what = e.what();
      const std::string prefix = f.info->name + ": ";
      if (what.rfind(prefix, 0) == 0) what = what.substr(prefix.size());
      throw std::invalid_argument(f.info->flag + ": " + what);
    }
  }
  render::validateParameters(values);
}

bool ParameterFlags::given(const std::string& name) const {
  for (const auto& f : flags_)
    if (f.info->name == name) return f.option->count() > 0;
  return false;
}

}  // namespace wb::app
