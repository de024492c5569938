#include "sweep/latest_link.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace lb {

namespace fs = std::filesystem;

void pointLatestAt(const std::string& runDir) {
  fs::path run = fs::path(runDir).lexically_normal();
  if (run.filename().empty()) run = run.parent_path();  // "dir/" -> "dir"
  const fs::path parent = run.parent_path();
  if (parent.empty() || run.filename() == "latest") return;
  const fs::path link = parent / "latest";
  std::error_code ec;
  if (fs::is_directory(fs::symlink_status(link, ec))) {
    std::fprintf(stderr, "lodbench: %s is a directory; not pointing it at the newest run\n", link.c_str());
    return;
  }
  // A temporary name per process, renamed over the old link: shards sharing a folder never see
  // a missing or half-written `latest`.
  const fs::path tmp = parent / (".latest." + std::to_string(getpid()) + ".tmp");
  fs::remove(tmp, ec);
  fs::create_symlink(run.filename(), tmp, ec);
  if (ec) {  // e.g. a filesystem without symlinks
    std::ofstream(tmp) << run.filename().string() << "\n";
    ec.clear();
  }
  fs::rename(tmp, link, ec);
  if (ec) {
    std::fprintf(stderr, "lodbench: could not point %s at %s: %s\n", link.c_str(), run.c_str(), ec.message().c_str());
    fs::remove(tmp, ec);
  }
}

}  // namespace lb
