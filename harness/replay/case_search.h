#pragma once
// A case's search for the configuration it draws: a matched search of its main parameter, or a
// tuned search over its configuration space (replay/matched.h), recorded as the case's "matched"
// (docs/results-format.md). The search is most of a matched case's time on a large terrain, so it
// is kept in a checkpoint file that a later invocation of the same run reads back instead of
// searching again: a sweep stopped by a deadline (a device call's limit) loses the timed frames of
// its unfinished cases, never their searches.
#include <nlohmann/json.hpp>
#include <string>

#include "camera/camera_path.h"
#include "config/config.h"
#include "render/scheme.h"

namespace lb {

struct Context;
struct Heightfield;

struct CaseSearch {
  ParamValues params;      // the parameters to draw
  int grid = 0;            // the patch grid a tuned search chose; 0: the case's own
  nlohmann::json matched;  // the search's record
};

// Runs the search of `c` under `config.match` (which must be on), or reads it from `checkpoint`
// where an earlier invocation wrote it for a case of the same digest (config/case_identity.h);
// writes the checkpoint after a search. An empty checkpoint path neither reads nor writes. A
// search read back says so in its record ("checkpoint").
CaseSearch searchCase(Context& ctx, const Scheme& scheme, const ParamValues& params, const Heightfield& terrain,
                      const CameraPath& path, const Config& config, const Case& c, const std::string& checkpoint);

}  // namespace lb
