#include "compare/ab.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "error.h"

namespace lb {

namespace fs = std::filesystem;

namespace {

// fork + execv rather than system(): no shell, so paths need no quoting. The child's stdout (the
// run directory) goes to stderr so that ours stays the verdict.
int runProcess(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::fflush(nullptr);
  pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed for " + argv[0]);
  if (pid == 0) {
    dup2(STDERR_FILENO, STDOUT_FILENO);
    execv(args[0], args.data());
    std::fprintf(stderr, "lodbench ab: cannot execute %s\n", args[0]);
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error("waitpid failed for " + argv[0]);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

void checkExecutable(const std::string& path, const char* flag) {
  if (!fs::is_regular_file(path) || access(path.c_str(), X_OK) != 0)
    throw InputError(std::string(flag) + ": '" + path + "' is not an executable file");
}

}  // namespace

AbRuns runAb(const AbOptions& o) {
  checkExecutable(o.baseline, "--baseline");
  checkExecutable(o.candidate, "--candidate");
  if (!fs::is_regular_file(o.config)) throw InputError(o.config + ": no such config file");
  if (o.rounds < 1) throw InputError("--rounds must be at least 1");
  fs::create_directories(o.outDir);
  std::vector<RunData> a, b;
  AbRuns runs;
  for (int round = 1; round <= o.rounds; ++round)
    for (int slot = 0; slot < 2; ++slot) {
      // A B, B A, A B, ...: each pair still runs side by side, and neither side always goes
      // second (which a drift of the machine, or any after-effect of the previous run, would favour).
      bool isA = (slot == 0) == (round % 2 == 1);
      const std::string& binary = isA ? o.baseline : o.candidate;
      std::string dir = o.outDir + "/" + (isA ? "a" : "b") + std::to_string(round);
      fs::remove_all(dir);  // a fresh run: resuming would skip every case and time nothing
      auto t0 = std::chrono::steady_clock::now();
      int rc = runProcess({binary, "run", o.config, "--out", dir, "--quiet"});
      double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (o.progress)
        std::fprintf(stderr, "lodbench ab: round %d/%d %s (%s): exit %d, %.1fs -> %s\n", round, o.rounds,
                     isA ? "A" : "B", binary.c_str(), rc, s, dir.c_str());
      if (rc == 2) throw InputError(binary + " run " + o.config + " rejected its input (exit 2)");
      if (rc != 0 && rc != 1)
        throw std::runtime_error(binary + " run " + o.config + " exited with " + std::to_string(rc));
      (isA ? a : b).push_back(loadRun(dir));
      runs.dirs.push_back(dir);
    }
  runs.baseline = poolRuns(a);
  runs.candidate = poolRuns(b);
  return runs;
}

}  // namespace lb
