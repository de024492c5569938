#pragma once
// Pareto front of a cost/error trade-off: both coordinates are "lower is better".
#include <cstddef>
#include <vector>

namespace lb {

// Indices of the points that no other point dominates (a point dominates another when it is
// no worse in both coordinates and better in at least one), sorted by x ascending. Exact
// duplicates are all kept: neither dominates the other. x and y must have the same size.
std::vector<size_t> paretoFront(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace lb
