#include "cbt_reference.h"

#include <bit>
#include <map>
#include <stdexcept>

#include "shaders/cbt_params.h"

namespace lbtest::cbt {

static uint32_t depthOf(uint32_t id) {
  return uint32_t(std::bit_width(id)) - 1;
}

Triangle triangle(uint32_t id, uint32_t latticeLog2) {
  const int64_t g = int64_t(1) << latticeLog2;
  const uint32_t d = depthOf(id);
  const bool second = (id >> (d - 1)) & 1u;
  Triangle t = second ? Triangle{{g, g}, {0, g}, {0, 0}} : Triangle{{0, 0}, {g, 0}, {g, g}};
  for (int k = int(d) - 2; k >= 0; --k) {
    const Point m{(t.a[0] + t.c[0]) / 2, (t.a[1] + t.c[1]) / 2};
    t = ((id >> k) & 1u) == 0 ? Triangle{t.b, m, t.a} : Triangle{t.c, m, t.b};
  }
  return t;
}

uint32_t edgeNeighbour(uint32_t id) {
  const uint32_t d = depthOf(id);
  uint32_t self = 2u | ((id >> (d - 1)) & 1u);
  uint32_t e = self ^ 1u, l = 0, r = 0;  // across the hypotenuse, the first leg, the second leg
  auto child = [](uint32_t n, uint32_t k) { return n == 0 ? 0 : 2 * n + k; };
  for (int k = int(d) - 2; k >= 0; --k) {
    const uint32_t bit = (id >> k) & 1u;
    if (bit == 0) {
      const uint32_t ne = child(l, 1), nl = 2 * self + 1, nr = child(e, 1);
      e = ne, l = nl, r = nr;
    } else {
      const uint32_t ne = child(r, 0), nl = child(e, 0), nr = 2 * self;
      e = ne, l = nl, r = nr;
    }
    self = 2 * self + bit;
  }
  return e;
}

std::string checkNeighbourRule(uint32_t maxDepth) {
  const uint32_t L = (maxDepth + 3) / 2;  // integer corners down to maxDepth
  const int64_t g = int64_t(1) << L;
  for (uint32_t d = 1; d <= maxDepth; ++d)
    for (uint32_t id = 1u << d; id < (2u << d); ++id) {
      const Triangle t = triangle(id, L);
      const uint32_t e = edgeNeighbour(id);
      const bool border =
          (t.a[0] == t.c[0] && (t.a[0] == 0 || t.a[0] == g)) || (t.a[1] == t.c[1] && (t.a[1] == 0 || t.a[1] == g));
      if (border != (e == 0))
        return "node " + std::to_string(id) + ": neighbour " + std::to_string(e) + ", hypotenuse on the border " +
               (border ? "yes" : "no");
      if (e == 0) continue;
      const Triangle n = triangle(e, L);
      if (depthOf(e) != d || n.a != t.c || n.c != t.a)
        return "node " + std::to_string(id) + ": neighbour " + std::to_string(e) + " does not share its hypotenuse";
    }
  return "";
}

std::vector<uint32_t> leaves(const std::vector<uint32_t>& state) {
  const uint32_t D = state.at(LB_CBT_DEPTH);
  const uint32_t sums = LB_CBT_HEADER + 2 * (1u << (D - 5));
  auto bits = [&](uint32_t id, uint32_t d) {  // set bits under node id of depth d
    const uint64_t first = uint64_t(id - (1u << d)) << (D - d), span = uint64_t(1) << (D - d);
    uint32_t n = 0;
    for (uint64_t b = first; b < first + span; ++b) n += (state.at(LB_CBT_HEADER + b / 32) >> (b % 32)) & 1u;
    return n;
  };
  for (uint32_t w = 0; w < (1u << (D - 5)); ++w)
    if (state.at(LB_CBT_HEADER + w) != state.at(LB_CBT_HEADER + (1u << (D - 5)) + w))
      throw std::runtime_error("the bitfield's copy disagrees with it at word " + std::to_string(w));
  for (uint32_t l = 0; l + 5 <= D; ++l)
    for (uint32_t k = 0; k < (1u << l); ++k)
      if (state.at(sums + (1u << l) + k) != bits((1u << l) + k, l))
        throw std::runtime_error("sum of level " + std::to_string(l) + " node " + std::to_string(k) +
                                 " disagrees with the bitfield");
  std::vector<uint32_t> out;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{1, 0}};
  while (!stack.empty()) {
    auto [id, d] = stack.back();
    stack.pop_back();
    const uint32_t n = bits(id, d);
    if (n == 0) throw std::runtime_error("node " + std::to_string(id) + " holds no leaf: a hole");
    if (n == 1 || d == D) {
      out.push_back(id);
      continue;
    }
    stack.push_back({2 * id + 1, d + 1});
    stack.push_back({2 * id, d + 1});
  }
  return out;
}

std::string conformity(const std::vector<uint32_t>& leafIds, uint32_t latticeLog2) {
  const int64_t g = int64_t(1) << latticeLog2;
  std::map<std::pair<Point, Point>, int> edges;
  for (uint32_t id : leafIds) {
    const Triangle t = triangle(id, latticeLog2);
    const Point v[3] = {t.a, t.b, t.c};
    for (int i = 0; i < 3; ++i) {
      Point p = v[i], q = v[(i + 1) % 3];
      if (q < p) std::swap(p, q);
      ++edges[{p, q}];
    }
  }
  for (const auto& [e, n] : edges) {
    const auto& [p, q] = e;
    const bool border = (p[0] == q[0] && (p[0] == 0 || p[0] == g)) || (p[1] == q[1] && (p[1] == 0 || p[1] == g));
    if (n != (border ? 1 : 2))
      return "edge (" + std::to_string(p[0]) + "," + std::to_string(p[1]) + ")-(" + std::to_string(q[0]) + "," +
             std::to_string(q[1]) + ") is used by " + std::to_string(n) + " leaves";
  }
  return "";
}

std::vector<uint32_t> withoutCounter(std::vector<uint32_t> state) {
  state.at(LB_CBT_UPDATES) = 0;
  return state;
}

}  // namespace lbtest::cbt
