#pragma once
// Joins the run directories of several shards (or machines) into one run.
#include <string>
#include <vector>

namespace lb {

struct MergeTotals {
  int cases = 0, duplicates = 0;
};

// Refuses (InputError) runs of different configs, tool versions, devices or drivers unless `force`.
MergeTotals mergeRuns(const std::string& outDir, const std::vector<std::string>& inputs, bool force);

}  // namespace lb
