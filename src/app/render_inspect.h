// `render --inspect-pixel X,Y [--inspect-samples N] --inspect-out FILE.json`: the path inspector headless.
// With --out the image is rendered as usual by the inspecting variant (the same image) and the first N
// samples of the pixel are recorded; without it only the pixel is traced, N samples.
#pragma once
#include "app/cmd_render.h"
#include "render/render_session.h"

namespace wb::app {

// Parses --inspect-pixel and checks the inspector's flags against the rest; throws std::invalid_argument.
void finishInspectFlags(RenderCommand& c);
// Switches the session's path tracer to the inspecting variant for the command's pixel and samples.
void startInspection(const RenderCommand& c, render::RenderSession& session);
// Writes --inspect-out from the records of the last render (`spp` samples traced for the pixel).
void writeInspection(const RenderCommand& c, render::RenderSession& session, uint32_t spp);
// Without --out: traces the pixel alone and writes --inspect-out. Returns the exit status.
int runInspectOnly(const RenderCommand& c, render::RenderSession& session);

}  // namespace wb::app
