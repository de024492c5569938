#pragma once
#include <cstddef>
#include <functional>
#include <vector>

namespace lb {

struct Summary {
  int count = 0;
  double mean = 0, median = 0, p5 = 0, p95 = 0, p99 = 0, min = 0, max = 0, stddev = 0;
};

// Percentile with linear interpolation between closest ranks (numpy's default), q in [0,100].
double percentile(std::vector<double> values, double q);
// The same percentile of n > 0 sorted values given by rank (at(i): the i-th smallest), for callers
// holding a histogram rather than the values (metrics/gpu_reduce.cpp); at() is called for at most two ranks.
double percentileOfSorted(size_t n, double q, const std::function<double(size_t)>& at);
Summary summarize(const std::vector<double>& values);

}  // namespace lb
