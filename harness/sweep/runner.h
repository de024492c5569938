#pragma once
// Replays every case of a config and writes results as it goes; a failing case is recorded as
// failed with its reason and the sweep goes on. Finished cases in an existing run dir are kept.
#include <stdexcept>
#include <string>
#include <vector>

#include "results/run_dir.h"
#include "sweep/config.h"
#include "sweep/results.h"

namespace lb {

struct Context;
class SweepProgress;

struct RunOptions {
  std::string outDir;      // run directory; "" = results/<name>/<utc-time>
  bool progress = true;    // progress line on stderr
  bool validation = false;
  int shardIndex = 0, shardCount = 1;  // run cases whose index % shardCount == shardIndex
  bool rerunChanged = false;  // resume: rerun finished cases whose inputs changed (else refuse)
};

// Thrown when a stop was requested (SIGINT/SIGTERM): the running case is dropped, finished ones stay.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};
// Async-signal-safe: sets a flag the replay loop checks between frames.
void requestStop();

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
// One case on an existing device context (used by tests and the sweep); progress may be null.
CaseResult runCase(Context& ctx, const Case& c, const Config& config, const std::string& imageDir,
                   SweepProgress* progress, ReferenceCache& refs);
RenderMode parseRenderMode(const std::string& name);
const char* renderModeName(RenderMode m);

}  // namespace lb
