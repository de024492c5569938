#include "compare/commands.h"

#include <cctype>
#include <cstdio>

#include "compare/verdict.h"
#include "error.h"
#include "results/write.h"

namespace lb {

// Exit 1 means "regression", so anything else that stops a check (an unwritable verdict path, a
// round that crashed) must not look like one: it becomes an InputError, exit 2.
template <typename F>
static int checked(F&& body) {
  try {
    return body();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(e.what());
  }
}

static int report(const CompareReport& r, const VerdictFiles& files) {
  std::fputs(verdictMarkdown(r).c_str(), stdout);
  writeVerdict(r, files.json, files.md);
  std::fprintf(stderr, "lodbench compare: %s; %d improved\n", verdictLine(r).c_str(), r.improvements());
  for (auto& n : r.notChecked) std::fprintf(stderr, "lodbench compare: NOT CHECKED: %s\n", n.c_str());
  return r.exitCode();
}

int compareCommand(const std::string& baselineDir, const std::vector<std::string>& candidateDirs,
                   const CompareOptions& options, const VerdictFiles& files) {
  return checked([&] {
    // Either side may be a folder of rounds (r1/, r2/, ...): rounds are the timing evidence.
    std::vector<RunData> rounds;
    for (auto& dir : candidateDirs)
      for (auto& r : loadRounds(dir)) rounds.push_back(std::move(r));
    return report(compareRuns(poolRuns(loadRounds(baselineDir)), poolRuns(rounds), options), files);
  });
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
  return checked([&] {
    AbRuns runs = runAb(ab);
    CompareOptions paired = options;
    paired.pairedRounds = true;  // round i of A and of B ran one after the other
    return report(compareRuns(runs.baseline, runs.candidate, paired), files);
  });
}

}  // namespace lb
