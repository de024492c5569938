#pragma once
#include <vector>

namespace lb {

struct Summary {
  int count = 0;
  double mean = 0, median = 0, p5 = 0, p95 = 0, p99 = 0, min = 0, max = 0, stddev = 0;
};

// Percentile with linear interpolation between closest ranks (numpy's default), q in [0,100].
double percentile(std::vector<double> values, double q);
Summary summarize(const std::vector<double>& values);

}  // namespace lb
