#include "render/uniform_instanced.h"

#include <cmath>

#include "shaders/shared.h"
#include "shaders/uniform_params.h"

namespace lb {
namespace {

class UniformInstancedLod : public InstancedLod {
 public:
  UniformInstancedLod(int level, int diagonal, int split) {
    // Footprint rows [r0, r1) of the level x level cells; all of them together are one patch.
    for (int s = 0; s < split; ++s) {
      Footprint f;
      f.name = "rows" + std::to_string(s);
      const int r0 = level * s / split, r1 = level * (s + 1) / split;
      for (int z = r0; z <= r1; ++z)
        for (int x = 0; x <= level; ++x) f.vertices.emplace_back(float(x), float(z));
      auto at = [&](int x, int z) { return uint32_t((z - r0) * (level + 1) + x); };
      for (int z = r0; z < r1; ++z)
        for (int x = 0; x < level; ++x) {
          uint32_t a = at(x, z), b = at(x + 1, z), c = at(x + 1, z + 1), d = at(x, z + 1);
          // 2, 3: the diagonal flips between the quadrants of the patch (towards or away from its centre).
          int diag = diagonal;
          if (diagonal >= 2) diag = ((2 * x < level) == (2 * z < level)) == (diagonal == 2) ? 0 : 1;
          if (diag == 0)
            f.indices.insert(f.indices.end(), {a, b, c, a, c, d});
          else
            f.indices.insert(f.indices.end(), {a, b, d, b, c, d});
        }
      if (!f.indices.empty()) footprints_.push_back(std::move(f));
    }
  }
  const std::vector<Footprint>& footprints() const override { return footprints_; }
  void select(const FrameUniforms& frame, Selection& out) const override {
    const int grid = int(frame.terrain.y);
    out.instances.assign(footprints_.size(), {});
    out.counters.clear();
    for (auto& list : out.instances)
      for (int j = 0; j < grid; ++j)
        for (int i = 0; i < grid; ++i) list.push_back({glm::vec4(float(i), float(j), 0, 0), glm::vec4(0)});
  }

 private:
  std::vector<Footprint> footprints_;
};

class UniformInstanced : public Scheme {
 public:
  const SchemeInfo& info() const override {
    static const SchemeInfo kInfo = {
        .name = "uniform-instanced",
        .description = "uniform's patches as instanced grids (probe and path tests; not registered)",
        .seed = "harness/render/uniform_instanced.h",
        .params = {{"level", LB_UNIFORM_LEVEL, 8, 1, 64, true, "cells per patch side"},
                   {"diagonal", 1, 0, 0, 3, true, "cell diagonal"},
                   {"split", 2, 1, 1, 64, true, "footprints per patch"}},
        .mainParam = "level",
        .path = DrawPath::InstancedGrid,
        .vert = "uniform_instanced",
    };
    return kInfo;
  }
  std::unique_ptr<InstancedLod> instancedLod(const Heightfield&, const ParamValues& v) const override {
    return std::make_unique<UniformInstancedLod>(int(v.at("level")), int(v.at("diagonal")), int(v.at("split")));
  }
};

}  // namespace

const Scheme& uniformInstancedScheme() {
  static const UniformInstanced scheme;
  return scheme;
}

}  // namespace lb
