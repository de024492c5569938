#include "compare/commands.h"

#include <cctype>
#include <cstdio>

#include "compare/verdict.h"
#include "sweep/results.h"

namespace lb {

static int report(const CompareReport& r, const VerdictFiles& files) {
  std::fputs(verdictMarkdown(r).c_str(), stdout);
  writeVerdict(r, files.json, files.md);
  std::fprintf(stderr, "lodbench compare: %s: %d of %zu cases regressed, %d improved\n",
               r.exitCode() ? "REGRESSION" : "clean", r.regressions(), r.cases.size(), r.improvements());
  return r.exitCode();
}

int compareCommand(const std::string& baselineDir, const std::vector<std::string>& candidateDirs,
                   const CompareOptions& options, const VerdictFiles& files) {
  RunData baseline = loadRun(baselineDir);
  std::vector<RunData> rounds;
  for (auto& dir : candidateDirs) rounds.push_back(loadRun(dir));
  return report(compareRuns(baseline, poolRuns(rounds), options), files);
}

int abCommand(AbOptions ab, const CompareOptions& options, VerdictFiles files) {
  if (ab.outDir.empty()) {
    std::string id;  // 2026-11-21T19:36:00Z -> 20261121-193600
    for (char ch : isoTimeUtc())
      if (std::isdigit(static_cast<unsigned char>(ch))) id += ch;
    ab.outDir = "results/ab/" + id.insert(8, "-");
  }
  if (files.json.empty()) files.json = ab.outDir + "/compare.json";
  if (files.md.empty()) files.md = ab.outDir + "/compare.md";
  AbRuns runs = runAb(ab);
  CompareOptions paired = options;
  paired.pairedRounds = true;  // round i of A and of B ran one after the other
  return report(compareRuns(runs.baseline, runs.candidate, paired), files);
}

}  // namespace lb
