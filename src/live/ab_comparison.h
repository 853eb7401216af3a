// The A/B comparison after a shader edit: the old and the new pipeline of each rebuilt pass rendered with the
// same seeds and sample sequence at a small budget, on a stand-in renderer (the live one's kind, mode, shader
// variant and parameters, at the A/B size), so the live accumulation is not touched. The stand-in's passes
// render with the live passes' own pipeline objects (the new one installed, the old one HotReload kept),
// which the driver has compiled already: a comparison builds and compiles nothing. The image and speed
// verdicts come from eval/ab.h.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "eval/ab.h"
#include "live/hot_reload.h"
#include "render/render_session.h"

namespace wb::live {

// What one comparison costs: the trace size, the samples of each side's image (one run per sample, seeds
// seed..seed+spp-1, each rendered by both sides: their spread is the paired noise) and the alternating timing
// rounds (each round times one sample of each side, the order flipping every round: ABBA).
struct ABBudget {
  uint32_t width = 64, height = 64;
  uint32_t spp = 4;
  uint32_t rounds = 5;
};

struct ABOutcome {
  ReloadAB result;
  eval::ImageRGBA oldImage, newImage;  // the mean of each side's runs
};

class ABComparison {
 public:
  ABComparison(render::RenderSession& session, ABBudget budget = {});
  ~ABComparison();
  ABComparison(const ABComparison&) = delete;
  ABComparison& operator=(const ABComparison&) = delete;

  const ABBudget& budget() const { return budget_; }
  void setBudget(const ABBudget& budget) { budget_ = budget; }

  // Render thread: makes the stand-ins of the session's renderers now, so that the first comparison does not
  // pay for their images and buffers.
  void prepare();
  // Render thread, after the reload's pipelines are installed (HotReload::lastInstalled()): one outcome per
  // installed pass of a session renderer, the active renderer's first. Throws on a device error.
  std::vector<ABOutcome> compare(const std::vector<HotReload::InstalledPass>& installed);
  // Forgets the stand-in renderers: after a reload that was not compared or a revert their pipelines are no
  // longer the live ones (the next comparison makes them again).
  void reset() { standIns_.clear(); }

 private:
  // The stand-in of `live`, made on first use, with live's parameters at the A/B size and live's installed
  // pipelines (shared: compiled by the driver already).
  render::Renderer& standIn(render::Renderer& live);
  // Installs `pipeline` (a live pass's) into the stand-in's `standIn` pass unless it has it already.
  static void use(render::Pass& standIn, const render::PassPipeline& pipeline);
  ABOutcome compareOne(const HotReload::InstalledPass& ip);

  render::RenderSession& session_;
  ABBudget budget_;
  std::map<const render::Renderer*, std::unique_ptr<render::Renderer>> standIns_;
};

}  // namespace wb::live
