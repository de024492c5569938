#pragma once
// Joins the run directories of several shards (or machines) into one run. Schedulers retry: a
// shard folder may be given twice, or a re-run of a shard may sit beside the attempt it replaced,
// so the output depends on the set of folders alone (not their order, not how often one is named)
// and two copies of one case are either the same bytes or refused (docs/results-format.md,
// "Merging shards").
#include <string>
#include <vector>

namespace lb {

struct MergeTotals {
  int cases = 0;                   // cases in the merged run
  int duplicates = 0;              // further copies of those cases, left out (byte-identical, or superseded)
  int folders = 0;                 // distinct folders merged (a folder named twice counts once)
  std::vector<std::string> notes;  // copies left out that were not byte-identical (superseded attempts)
};

// Refuses (InputError) runs of different configs, tool versions, devices or drivers unless `force`,
// and, force or not, two copies of a case that differ (naming the case and both folders), unless
// one is finished ("ok") and the others are not: a finished copy supersedes failed and skipped ones.
MergeTotals mergeRuns(const std::string& outDir, const std::vector<std::string>& inputs, bool force);

}  // namespace lb
