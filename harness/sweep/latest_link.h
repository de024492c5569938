#pragma once
// results/<name>/latest: where the newest run of a config is, so scripts and people need not
// look up its time-stamped id.
#include <string>

namespace lb {

// Points <parent of runDir>/latest at runDir (a relative symlink; where symlinks cannot be made, a
// file holding the run's folder name). Only in a config's results folder: when runDir is the
// default results/<name>/<run-id> (defaultDir) or its parent folder is named after the config, so
// `--out /tmp/x` leaves /tmp alone. A `latest` that is a real directory is left as it is. Never
// fails the run: a problem is one line on stderr.
void pointLatestAt(const std::string& runDir, const std::string& configName, bool defaultDir);

}  // namespace lb
