#pragma once
// The compare and ab subcommands behind the CLI (harness/cli/main.cpp only wires their flags).
#include <string>
#include <vector>

#include "compare/ab.h"
#include "compare/compare.h"

namespace lb {

struct VerdictFiles {
  std::string json, md;  // "" = not written
};

// Prints the Markdown verdict on stdout, writes the files, returns 0 (clean) or 1 (regression).
// Several candidate directories are rounds of one config, pooled (poolRuns).
int compareCommand(const std::string& baselineDir, const std::vector<std::string>& candidateDirs,
                   const CompareOptions& options, const VerdictFiles& files);
// Runs the rounds, then compares; verdict files default to <out>/compare.{json,md}.
// Both return 0 or 1 and throw InputError (exit 2) for anything that stops the check.
int abCommand(AbOptions ab, const CompareOptions& options, VerdictFiles files);

}  // namespace lb
