#pragma once
// A/B mode: the same config run by two lodbench binaries, interleaved A B B A A B ... so that slow
// drifts of the machine (clock, load, thermal) fall on both sides alike. Each round is a full
// `run --quiet` into its own directory; the rounds of each side are pooled for compareRuns.
#include <string>
#include <vector>

#include "compare/run_data.h"

namespace lb {

struct AbOptions {
  std::string baseline, candidate;  // lodbench executables
  std::string config;               // config file both run
  std::string outDir;               // rounds go to <outDir>/a1, b1, b2, a2, a3, b3, ...
  int rounds = 3;
  bool progress = true;  // one line per round on stderr
};

struct AbRuns {
  RunData baseline, candidate;    // pooled over rounds
  std::vector<std::string> dirs;  // every round's directory, in run order
};

// Throws InputError for a binary that is not an executable file or a missing config, and
// std::runtime_error when a round's process cannot start or exits with neither 0 nor 1
// (1 = some case failed: its results are still there and compare reports it).
AbRuns runAb(const AbOptions& options);

}  // namespace lb
