#pragma once
// `run --dry-run`: the cases a config (or shard) would run, how long they would take and how much
// disk they would fill, without opening a device or writing anything.
#include <string>

namespace lb {

struct Config;

// Prints the case ids on stdout, then on stderr: the case count, what an existing --out folder
// would keep, an estimated time from the costs of the newest earlier run of the same results
// folder (or that there is none to estimate from) and an estimated disk size. Returns 0.
int dryRun(const Config& config, const std::string& outDir, int shardIndex, int shardCount, bool shardGiven);

}  // namespace lb
