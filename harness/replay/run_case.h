#pragma once
// Replays one case: loads its terrain and path, runs its timed frames, timing-mode replays,
// measurement passes and images, in that order, and returns what it measured (results/write.h
// records it). The timed frames come first, so nothing else perturbs them.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "config/config.h"
#include "render/frame_data.h"
#include "replay/case_progress.h"
#include "replay/raycast_cache.h"
#include "results/write.h"

namespace lb {

struct Context;

// Thrown when a stop was requested (SIGINT/SIGTERM): the running case is dropped, finished ones stay.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};
// Async-signal-safe: sets a flag the replay loop checks between frames.
void requestStop();
void clearStop();  // a new sweep starts unstopped

// One case on an existing device context (used by tests and the sweep); progress may be null.
// searchCheckpoint: where a matched case keeps its search for a later invocation
// (replay/case_search.h); empty: nowhere.
CaseResult runCase(Context& ctx, const Case& c, const Config& config, const std::string& imageDir,
                   CaseProgress* progress, ReferenceCache& refs, const std::string& searchCheckpoint = "");

// Load-time stage costs per terrain label of the cases run since clearStageCosts (run.json
// costs.terrains): each stage's largest figure over the cases, the one that did the work.
void clearStageCosts();
void recordStageCosts(const std::string& terrain, const std::string& scheme, double loadS, double pagesS,
                      double normalMapS, double preprocessS);
nlohmann::json stageCostsJson();

RenderMode parseRenderMode(const std::string& name);

}  // namespace lb
