// The panel's widgets for the parameters (render/parameters.h), generated from their declarations: a checkbox
// per Bool, a slider or input per number (clamped to the valid range), a combo per choice, a colour editor,
// a path field with a Load button.
#pragma once
#include <string>

#include "render/parameters.h"

namespace wb::app {

// One parameter's widget; returns true when it changed the value.
bool drawParameter(const render::ParameterInfo& p, render::Parameters& values);
// Every parameter of `group` that `mode` uses, in declaration order; returns true when one changed.
bool drawParameterGroup(const std::string& group, render::Parameters& values, render::RenderMode mode);

}  // namespace wb::app
