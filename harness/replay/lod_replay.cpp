#include "replay/lod_replay.h"

#include <stdexcept>
#include <string>

#include "render/lod_state.h"
#include "render/renderer.h"
#include "sha256.h"

namespace lb {

// convergeLod without the state's hash.
static ConvergeResult converge(Renderer& r, const CameraPose& pose) {
  LodState& lod = r.lodState();
  lod.reset();
  ConvergeResult out;
  const int limit = int(lod.gpuLod().convergeLimit);
  uint32_t last = 0;
  int steady = 0;
  while (out.updates < limit) {
    uint32_t n = lod.update(pose);
    ++out.updates;
    steady = out.updates > 1 && n == last ? steady + 1 : 0;
    last = n;
    if (steady >= kSteadyUpdates) {
      out.converged = true;
      break;
    }
  }
  out.instances = last;
  return out;
}

ConvergeResult convergeLod(Renderer& r, const CameraPose& pose) {
  ConvergeResult out = converge(r, pose);
  LodState& lod = r.lodState();
  std::vector<uint32_t> state = lod.read();
  const GpuLod& g = lod.gpuLod();
  if (g.treeWordCount > 0 && size_t(g.treeFirstWord) + g.treeWordCount <= state.size()) {
    state = std::vector<uint32_t>(state.begin() + g.treeFirstWord, state.begin() + g.treeFirstWord + g.treeWordCount);
  } else if (!state.empty()) {
    state[0] = 0;
  }
  out.stateSha256 =
      sha256Hex(std::string(reinterpret_cast<const char*>(state.data()), state.size() * sizeof(uint32_t)));
  return out;
}

void startLod(Renderer& r, const CameraPose& first, int warmup) {
  converge(r, first);
  for (int i = 0; i < warmup; ++i) r.lodState().update(first);
  r.lodState().snapshot();
}

nlohmann::json lodStateJson(const ConvergeResult& c, const std::vector<std::pair<std::string, double>>& facts) {
  nlohmann::json out = {{"converge_updates", c.updates},
                        {"lod_converged", c.converged},
                        {"converged_instances", c.instances},
                        {"converged_state_sha256", c.stateSha256}};
  for (const auto& [k, v] : facts) out[k] = v;
  return out;
}

static std::runtime_error diverged(const std::string& what, int frame, uint32_t got, uint32_t want) {
  return std::runtime_error("LOD replay diverged: " + what + " frame " + std::to_string(frame) + " has " +
                            std::to_string(got) + " instances, the first timed repetition " + std::to_string(want));
}

std::vector<uint32_t> timedInstances(const std::vector<FrameResult>& frames, int framesPerRep) {
  std::vector<uint32_t> first;
  for (size_t i = 0; i < frames.size(); ++i) {
    if (i < size_t(framesPerRep)) {
      first.push_back(frames[i].instances);
    } else if (frames[i].instances != first[i % size_t(framesPerRep)]) {
      throw diverged("repetition " + std::to_string(i / size_t(framesPerRep) + 1), frames[i].frame, frames[i].instances,
                     first[i % size_t(framesPerRep)]);
    }
  }
  return first;
}

LodReplay::LodReplay(Renderer& r, std::function<CameraPose(int)> pose, std::vector<uint32_t> expected)
    : lod_(r.lodState()), pose_(std::move(pose)), expected_(std::move(expected)) {
  restart();
}

void LodReplay::restart() {
  lod_.restore();
  next_ = 0;
}

void LodReplay::advanceTo(int frame) {
  if (frame < next_ - 1) throw std::logic_error("LodReplay: frame " + std::to_string(frame) + " is behind the replay");
  for (; next_ <= frame; ++next_) {
    uint32_t n = lod_.update(pose_(next_));
    if (lod_.overflow() > 0)  // the timed frame drew the same state: these instances were missing
      throw std::runtime_error("LOD state overflow: frame " + std::to_string(next_) + " has " +
                               std::to_string(lod_.overflow()) + " instances beyond the " +
                               std::to_string(lod_.gpuLod().maxInstances) + " the renderer holds, left undrawn");
    if (size_t(next_) < expected_.size() && n != expected_[size_t(next_)])
      throw diverged("the replay's", next_, n, expected_[size_t(next_)]);
  }
}

}  // namespace lb
