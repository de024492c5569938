#pragma once
// Replays every case of a config and writes results as it goes; a failing case is recorded as
// failed with its reason and the sweep goes on. Finished cases in an existing run dir are kept.
#include <string>

#include "sweep/config.h"
#include "sweep/results.h"

namespace lb {

struct Context;

struct RunOptions {
  std::string outDir;      // run directory; "" = results/<name>/<utc-time>
  bool progress = true;    // progress line on stderr
  bool validation = false;
};

struct RunTotals {
  std::string dir;
  int ok = 0, failed = 0, skipped = 0, resumed = 0;
  int validationErrors = 0;  // when the validation layer was on
};

RunTotals runSweep(const Config& config, const RunOptions& options);
// One case on an existing device context (used by tests and the sweep).
CaseResult runCase(Context& ctx, const Case& c, const Config& config, const std::string& imageDir, bool progress,
                   ReferenceCache& refs);
RenderMode parseRenderMode(const std::string& name);
const char* renderModeName(RenderMode m);

}  // namespace lb
