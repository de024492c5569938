#pragma once
// The run directory (docs/results-format.md) has one owner: this module reads run.json and
// cases/*.json for every command (run/resume, merge, report, compare, gbench) with one error
// policy: a file that is missing where it must exist, not JSON, or not a lodbench file is an
// InputError naming it, never skipped. It also rebuilds the aggregates and decides what a resumed
// run may keep (by the case digests, see case_identity.h).
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

namespace lb {

struct Case;

// Reads and parses a JSON file; InputError "<file>: ..." when it is missing or not JSON.
nlohmann::json readJsonFile(const std::string& file);

bool hasRunJson(const std::string& dir);
// dir/run.json, checked to be a lodbench run file (an object with a "context" object).
nlohmann::json readRunJson(const std::string& dir);

struct CaseFile {
  std::string file;  // path of cases/<id>.json
  nlohmann::json doc;
  std::string id() const { return doc["case_id"].get<std::string>(); }
};
// Every cases/*.json of dir, sorted by file name, each checked to be a case file (an object with a
// string "case_id" and a "frames" array); two files with one case_id are an error. No cases/
// directory reads as no cases. Cases dir/run.json lists in "stale_cases" (a grown sweep's cases no
// longer in its config) are left out unless includeStale: every reader sees the run as it is now.
std::vector<CaseFile> readCaseFiles(const std::string& dir, bool includeStale = false);

// Rebuilds frames.csv and summary.json of a run directory from its case files.
void writeAggregates(const std::string& dir, const nlohmann::json& context);

// What a resumed run keeps. A finished ("ok") case file is reused only when its recorded input
// digest equals the case's digest now; failed and skipped cases run again.
//
// A case file is the case of the same id, or else the case of the same digest: ids name the
// parameters a config lists, digests every parameter with its resolved value, so a config that
// now lists a parameter at its default (or no longer lists one it listed at its default) has the
// same cases under other ids. Such a case takes the id it was recorded with (planResume renames it
// in `cases`), so it is kept, not run again beside a stale copy of itself.
struct ResumePlan {
  std::set<std::string> reuse;       // case ids kept as they are
  std::vector<std::string> changed;  // "<id>: <what changed>" for ok cases whose inputs changed
  std::vector<std::string> stale;    // ids of case files of no case of the config now (kept on disk)
  std::vector<std::string> renamed;  // "<recorded id> (listed now as <id of the config>)"
  // "<id>: <what changed>" for ok cases whose inputs differ only in their plugin (a rebuilt scheme
  // library): run again without asking, as new cases are.
  std::vector<std::string> rebuilt;
};
ResumePlan planResume(const std::string& dir, std::vector<Case>& cases);

// The checks `run` makes before reusing an existing directory, so that a sweep can grow: the same
// tool version (checkToolVersion), the same shard, and (unless rerunChanged) no finished case whose
// inputs changed. Cases new to the config simply run; case files of cases no longer in it are
// stale: kept, named on stderr, and listed by the caller in run.json. Throws InputError naming
// the directory, the cases and what changed. The config itself may differ: the digests decide.
ResumePlan checkResume(const std::string& dir, const nlohmann::json& previousRun, int shardIndex, int shardCount,
                       std::vector<Case>& cases, bool rerunChanged);
// A folder written by another tool version: an InputError saying which version wrote it and what to do.
void checkToolVersion(const std::string& dir, const nlohmann::json& previousRun);
// Resuming on another device or driver would mix two devices' timings in one run: an InputError.
void checkSameDevice(const std::string& dir, const nlohmann::json& previousRun, const nlohmann::json& context);

}  // namespace lb
