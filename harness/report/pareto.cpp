#include "report/pareto.h"

#include <algorithm>
#include <cassert>
#include <numeric>

namespace lb {

std::vector<size_t> paretoFront(const std::vector<double>& x, const std::vector<double>& y) {
  assert(x.size() == y.size());
  std::vector<size_t> order(x.size());
  std::iota(order.begin(), order.end(), size_t(0));
  // Sweep by x ascending (ties: y ascending); a point is on the front when its y is below every
  // y seen so far, or equal to the last front point's y at the same x (an exact duplicate).
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return x[a] != x[b] ? x[a] < x[b] : y[a] < y[b]; });
  std::vector<size_t> front;
  for (size_t i : order) {
    if (front.empty() || y[i] < y[front.back()]) {
      front.push_back(i);
    } else if (x[i] == x[front.back()] && y[i] == y[front.back()]) {
      front.push_back(i);
    }
  }
  return front;
}

}  // namespace lb
