#pragma once
// A CPU reading of `cbt`'s state (shaders/cbt_params.h, shaders/cbt.glsl) for tests: leaves, their
// triangles, the neighbour rule checked against geometry, and the conformity of a leaf set.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace lbtest::cbt {

using Point = std::array<int64_t, 2>;
struct Triangle {
  Point a, b, c;  // hypotenuse a-c, right angle at b
};

// Node id's triangle in a square of 2^latticeLog2 units (depth >= 1), as shaders/cbt.glsl builds it.
Triangle triangle(uint32_t id, uint32_t latticeLog2);
// The same-depth node across id's hypotenuse by shaders/cbt.glsl's rule (0: the border).
uint32_t edgeNeighbour(uint32_t id);
// "" when the rule agrees with the geometry for every node down to maxDepth, else the first failure.
std::string checkNeighbourRule(uint32_t maxDepth);

// The leaves of a state, left to right, read from its bitfield alone; throws when a subtree holds
// no bit (a hole) or the stored sums disagree with the bits.
std::vector<uint32_t> leaves(const std::vector<uint32_t>& state);
// "" when every leaf edge is shared by exactly one other leaf's identical edge or lies on the
// square's border (no T-junction), else the first offending edge.
std::string conformity(const std::vector<uint32_t>& leafIds, uint32_t latticeLog2);
// The state without its update counter (word 0), for comparing states across updates.
std::vector<uint32_t> withoutCounter(std::vector<uint32_t> state);

}  // namespace lbtest::cbt
