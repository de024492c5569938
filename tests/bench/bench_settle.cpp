// What a stateful LOD's measurement repeats for every frame of a path (replay/settle.h) and every
// trial of a matched search: cbt's update, its state set aside and put back (through the host, as
// LodState::read and load do, or on the device, as keep and putBack do) and an error map read back,
// on cbt at depth 25 (16 MiB of state, as cells_per_texel 2 makes on the suite's 16385^2 terrain)
// at 1920x1080. Also the host's read of a buffer the device wrote, in the memory type createBuffer
// gives a host-visible storage buffer and in createReadBackBuffer's (host-cached where the device
// has it). The device is lavapipe unless LODBENCH_BENCH_DEVICE names another.
#include <cstdlib>
#include <cstring>
#include <memory>

#include "bench.h"
#include "camera/camera_path.h"
#include "render/lod_state.h"
#include "render/renderer.h"
#include "replay/lod_replay.h"
#include "schemes/registry.h"
#include "terrain/heightfield.h"
#include "vk/context.h"

namespace lb {

namespace {

// One renderer for every benchmark here (made once: the pipelines take seconds on lavapipe), its
// cbt converged at frame 80 of the flyover path over a 1025^2 terrain. Depth 2 (14 - subd 2) + 1
// = 25: 1024 spacings x cells_per_texel 16 = 2^14 lattice units a side.
struct Settle {
  Heightfield hf;
  CameraPose pose;
  std::unique_ptr<Renderer> r;
};

Settle& settle() {
  static Settle* s = [] {
    Context& ctx = benchContext();
    auto* out = new Settle();
    TerrainSpec spec;
    spec.size = 1025;
    spec.extent = 4000;
    spec.heightScale = 400;
    out->hf = makeHeightfield(spec);
    out->pose =
        samplePose(loadCameraPath(std::string(LODBENCH_SOURCE_DIR) + "/configs/paths/flyover.csv"), 30, 80, out->hf);
    out->r = std::make_unique<Renderer>(ctx, out->hf, RenderSettings{1920, 1080, 16});
    out->r->setScheme(*findScheme("cbt"), {{"subd", 2}, {"cells_per_texel", 16}});
    for (int i = 0; i < 60; ++i) out->r->lodState().update(out->pose);
    std::atexit([] { settle().r.reset(); });  // before the context (registered earlier, runs later)
    return out;
  }();
  return *s;
}

void label(benchmark::State& state) {
  Settle& s = settle();
  state.counters["state_mib"] = double(s.r->lodState().read().size() * 4) / (1024.0 * 1024.0);
  state.SetLabel(benchContext().props.deviceName);
}

}  // namespace

void benchCbtUpdate(benchmark::State& state) {
  Settle& s = settle();
  for (auto _ : state) benchmark::DoNotOptimize(s.r->lodState().update(s.pose));
  label(state);
}

void benchCbtStateAside(benchmark::State& state, bool onDevice) {
  Settle& s = settle();
  LodState& lod = s.r->lodState();
  for (auto _ : state) {
    if (onDevice) {
      lod.keep();
      lod.putBack();
    } else {
      const std::vector<uint32_t> saved = lod.read();
      lod.load(saved);
    }
  }
  label(state);
}

void benchCbtErrorMap(benchmark::State& state) {
  Settle& s = settle();
  FrozenLod frozen(*s.r);
  for (auto _ : state) benchmark::DoNotOptimize(s.r->renderErrorMap(s.pose, s.pose));
  label(state);
}

void benchHostRead(benchmark::State& state, VkDeviceSize bytes, bool readBack) {
  Context& ctx = benchContext();
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  Buffer b = readBack ? createReadBackBuffer(ctx, bytes, usage) : createBuffer(ctx, bytes, usage, true);
  std::memset(b.mapped, 1, size_t(bytes));
  std::vector<uint8_t> host(static_cast<size_t>(bytes));
  for (auto _ : state) {
    std::memcpy(host.data(), b.mapped, host.size());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(bytes));
  state.SetLabel(ctx.props.deviceName);
}

}  // namespace lb
