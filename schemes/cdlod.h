#pragma once
// What cdlod (schemes/cdlod.cpp) and cdlod-sse (schemes/cdlod_sse.cpp) share: the quadtree of
// nodes over the lattice with its min-max pyramid (schemes/preprocess/min_max_pyramid.h), the
// footprint of one node quadrant, the frame's camera and ranges, the per-frame node flags and the
// emission of a quadrant as an instance, and the parameters both take. schemes/cdlod.cpp's head
// comment gives the nodes and the constants; each scheme's file its own selection rule.
#include <glm/glm.hpp>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "render/instanced.h"
#include "render/scheme.h"
#include "schemes/preprocess/min_max_pyramid.h"

namespace lb {
namespace cdlod {

bool isPowerOfTwo(double v);
int log2Int(int v);

struct Box {
  glm::dvec3 lo, hi;
};
double boxDistance2(const Box& b, const glm::dvec3& p);
bool outsidePlanes(const Box& b, const glm::dvec4* planes);

struct Settings {
  bool sse = false;
  double triSize = 3, morph = 0.3, maxError = 1, cellsPerTexel = 1;
  bool morphOn = true;
  int nodeCells = 0;
};
// The parameters both schemes take besides their main one, and the settings they give.
std::vector<ParamSpec> commonParams();
Settings settingsFrom(const ParamValues& v, bool sse);
void validateParams(const std::string& scheme, const ParamValues& v);

// Node state of one frame, per pyramid block.
enum : uint8_t {
  kQuadrants = 0x0f,  // cdlod: quadrants this node draws at its own level (bit = child x + 2 child z)
  kVisited = 0x10,    // in range (or the root) and not culled
  kLeaf = 0x20,       // cdlod-sse: drawn whole
  kRefined = 0x40,    // cdlod-sse: its unculled children are in the tree
};

struct NodeRef {
  int p, i, j;
};

// The nodes over the lattice and one frame's state of them. select() clears the last frame's flags,
// takes the frame's camera and ranges (prepare) and hands over to the scheme's rule (selectNodes).
class NodeTree : public InstancedLod {
 public:
  // `candidates`: the node sizes (cells a side) the scheme may draw, one footprint each.
  NodeTree(const Heightfield& hf, const Settings& s, std::vector<int> candidates);
  const std::vector<Footprint>& footprints() const override { return footprints_; }
  void select(const FrameUniforms& frame, Selection& out) const override;

 protected:
  virtual void selectNodes(const FrameUniforms& frame, Selection& out) const = 0;

  static Footprint footprint(int n);
  int finestLevelUsed(int n) const;
  void allocateFlags() const;
  void prepare(const FrameUniforms& frame) const;
  Box box(int p, int i, int j) const;
  Box rectBox(double x0, double z0, double s, double hmin, double hmax) const;
  // The box of child region (ci, cj) of a node at pyramid level p; level 0 has no finer blocks,
  // so its quadrants take their node's heights.
  Box quadrantBox(int p, int ci, int cj) const;
  bool childInside(int p, int ci, int cj) const;
  bool inRange(const Box& b, int level) const { return boxDistance2(b, eye_) <= range_[level] * range_[level]; }
  uint8_t& flags(int p, int i, int j) const { return flags_[size_t(p)][pyr_.index(p, i, j)]; }
  void touch(int p, int i, int j, uint8_t f) const;
  void emit(Selection& out, int p, int ci, int cj, int level, const glm::vec4& kb, float kNode) const;

  static constexpr int kMaxLevels = 32;
  Settings s_;
  std::vector<int> candidates_;
  // The terrain must outlive the tree: a frame that draws a smaller node size than any before
  // makes the pyramid's finer levels from it (under mutex_, like every frame's state).
  const Heightfield* hf_;
  mutable MinMaxPyramid pyr_;
  std::vector<Footprint> footprints_;
  // Per-frame state: select() is const for its callers and reuses these (no allocation once warm).
  mutable std::mutex mutex_;
  mutable std::vector<std::vector<uint8_t>> flags_;
  mutable std::vector<NodeRef> touched_;
  mutable glm::dvec3 eye_{0};
  mutable glm::dvec2 origin_{0};
  mutable glm::dvec4 planes_[6];
  mutable double K_ = 0;
  mutable double range_[kMaxLevels] = {}, start_[kMaxLevels] = {}, end_[kMaxLevels] = {};
  mutable size_t fp_ = 0;
  mutable int n_ = 0, rootLevel_ = 0;
};

}  // namespace cdlod
}  // namespace lb
