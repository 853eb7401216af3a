#include "live/ab_comparison.h"

#include <algorithm>
#include <stdexcept>

namespace wb::live {

ABComparison::ABComparison(render::RenderSession& session, ABBudget budget)
    : session_(session), budget_(budget) {}

ABComparison::~ABComparison() = default;

render::Renderer& ABComparison::standIn(render::Renderer& live) {
  auto& s = standIns_[&live];
  // A stand-in made for another variant of the live renderer (its passes differ in number) is made anew.
  if (s && s->passes().size() != live.passes().size()) s.reset();
  render::RenderSettings settings = live.settings();
  settings.width = std::max(1u, budget_.width);
  settings.height = std::max(1u, budget_.height);
  settings.debugView = 0;  // the image the estimator gives, whatever the window shows
  settings.tileWidth = settings.tileHeight = 0;
  if (!s) {
    s = live.makeLike({session_.context(), session_.library(), session_.scene(), session_.gpuScene(),
                       session_.environment()},
                      settings);
  }
  s->matchCompiledParameters(live);
  if (auto* hybrid = dynamic_cast<render::HybridRenderer*>(s.get()))
    hybrid->setHybridSettings(session_.hybridSettings());
  s->setSettings(settings);
  s->setEnvironment(session_.environment());
  s->setLights(session_.lights());
  s->setCamera(session_.camera());
  // Every pass renders with the live one's pipeline (passes() come in the same order in both).
  const auto mine = s->passes(), theirs = live.passes();
  for (size_t i = 0; i < mine.size(); ++i) use(*mine[i], theirs[i]->installed());
  return *s;
}

void ABComparison::use(render::Pass& standIn, const render::PassPipeline& pipeline) {
  if (!pipeline || standIn.installed().pipeline == pipeline.pipeline) return;
  // The stand-in's pass takes the live pass's pipeline as its own program's.
  render::PassPipeline p = pipeline;
  p.program = standIn.program();
  standIn.install(std::move(p));
}

ABOutcome ABComparison::compareOne(const HotReload::InstalledPass& ip) {
  render::Renderer& live = *ip.owner;
  render::Renderer& s = standIn(live);
  const auto passes = s.passes();
  if (ip.passIndex >= passes.size()) throw std::runtime_error("A/B: the stand-in lacks " + ip.name);
  render::Pass& pass = *passes[ip.passIndex];
  // The two sides: the pipeline the reload replaced, and the live pass's new one.
  const render::PassPipeline sides[2] = {ip.before, ip.pass->installed()};
  if (!sides[0] || !sides[1]) throw std::runtime_error("A/B: no old or new pipeline for " + ip.name);
  auto use = [&](int side) { this->use(pass, sides[side]); };
  render::RenderSettings settings = s.settings();
  const uint32_t baseSeed = settings.seed;
  auto seed = [&](uint32_t k) {
    settings.seed = baseSeed + k;
    s.setSettings(settings);  // restarts accumulation with that seed
  };

  // The images: run k of each side with seed k, one sample each; the side that goes first alternates.
  const uint32_t runs = std::max(1u, budget_.spp);
  std::vector<eval::ImageRGBA> images[2];
  for (uint32_t k = 0; k < runs; ++k) {
    for (int i = 0; i < 2; ++i) {
      const int side = (k % 2 == 0) ? i : 1 - i;
      use(side);
      seed(k);
      s.render(1);
      images[side].push_back(s.readEstimate());  // the estimator's image: the verdict is not the denoiser's
    }
  }
  // The speed: rounds of one sample per side, back to back, the order flipping every round (ABBA) so that a
  // steady drift in the machine's load favours neither side. Every round renders the same sample (seed 0,
  // sample 0) on both sides: the same paths, the same work.
  std::vector<double> ms[2];
  for (uint32_t r = 0; r < std::max(1u, budget_.rounds); ++r) {
    for (int i = 0; i < 2; ++i) {
      const int side = (r % 2 == 0) ? 1 - i : i;  // even rounds: new then old; odd rounds: old then new
      use(side);
      seed(0);
      ms[side].push_back(1000.0 * s.render(1).front());
    }
  }
  use(1);  // the stand-in keeps the live renderer's pipeline
  settings.seed = baseSeed;
  s.setSettings(settings);

  ABOutcome o;
  o.result.pipeline = ip.name;
  o.result.mode = render::renderModeName(live.mode());
  o.result.active = &live == &session_.renderer();
  o.result.image = eval::compareImages(images[0], images[1]);
  o.result.speed = eval::compareSpeed(ms[0], ms[1]);
  auto mean = [](const std::vector<eval::ImageRGBA>& v) {
    eval::ImageRGBA m = v.front();
    for (size_t p = 0; p < m.pixels.size(); ++p) {
      double sum = 0;
      for (const auto& img : v) sum += img.pixels[p];
      m.pixels[p] = float(sum / double(v.size()));
    }
    return m;
  };
  o.oldImage = mean(images[0]);
  o.newImage = mean(images[1]);
  return o;
}

void ABComparison::prepare() {
  session_.forEachRenderer([&](render::Renderer& live) { standIn(live); });
}

std::vector<ABOutcome> ABComparison::compare(const std::vector<HotReload::InstalledPass>& installed) {
  std::vector<ABOutcome> out;
  for (const auto& ip : installed) {
    // Only the session's renderers are compared (a pass added by hand has no stand-in).
    bool ours = false;
    session_.forEachRenderer([&](render::Renderer& r) { ours = ours || &r == ip.owner; });
    if (!ours) continue;
    out.push_back(compareOne(ip));
  }
  std::stable_partition(out.begin(), out.end(), [](const ABOutcome& o) { return o.result.active; });
  return out;
}

}  // namespace wb::live
