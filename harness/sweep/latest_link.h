#pragma once
// results/<name>/latest: where the newest run of a config is, so scripts and people need not
// look up its time-stamped id.
#include <string>

namespace lb {

// Points <parent of runDir>/latest at runDir (a relative symlink; where symlinks cannot be made, a
// file holding the run's folder name). Only for the default run folder results/<name>/<run-id>:
// a folder given with --out is the caller's to name, and folders of rounds or shards
// (results/baseline/ci/r1, r2, ...) must not gain an extra run directory that readers of every
// subfolder would count twice. A `latest` that is a real directory is left as it is. Never fails
// the run: a problem is one line on stderr.
void pointLatestAt(const std::string& runDir);

}  // namespace lb
