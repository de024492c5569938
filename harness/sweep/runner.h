#pragma once
// Replays every case of a config and writes results as it goes; a failing case is recorded as
// failed with its reason and the sweep goes on. Finished cases in an existing run dir are kept.
#include <string>
#include <vector>

#include "config/config.h"
#include "replay/run_case.h"

namespace lb {

struct RunOptions {
  std::string outDir;    // run directory; "" = results/<name>/<utc-time>
  bool progress = true;  // progress line on stderr
  bool validation = false;
  int shardIndex = 0, shardCount = 1;  // run cases whose index % shardCount == shardIndex
  bool rerunChanged = false;           // resume: rerun finished cases whose inputs changed (else refuse)
};

struct RunTotals {
  std::string dir;
  int ok = 0, failed = 0, skipped = 0, resumed = 0;
  int validationErrors = 0;  // when the validation layer was on
  bool interrupted = false;
};

RunTotals runSweep(const Config& config, const RunOptions& options);
// The cases this shard runs, in order (deterministic for a config).
std::vector<Case> shardCases(const Config& config, int shardIndex, int shardCount);
// Parses "i/n" (0 <= i < n); throws InputError naming the flag.
void parseShard(const std::string& text, int& index, int& count);

}  // namespace lb
