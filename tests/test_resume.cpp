// Result identity and resume: case ids never collide, duplicates are errors, resume
// reuses a finished case only when its input digest is unchanged, --shard must match the
// folder's, and a sweep killed with SIGKILL at random moments resumes to results equal, counter
// for counter, to an uninterrupted run.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "config/case_identity.h"
#include "config/config.h"
#include "error.h"
#include "results/run_dir.h"
#include "sha256.h"
#include "sweep/runner.h"

using namespace lb;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

const std::string kConfigs = std::string(LODBENCH_SOURCE_DIR) + "/configs";

fs::path fresh(const std::string& name) {
  // Not "lodbench_resume": test_results.cpp wipes that one, and ctest -j2 runs both at once.
  fs::path d = fs::path(::testing::TempDir()) / "lodbench_test_resume" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Config config(const std::string& body, const std::string& baseDir = kConfigs) {
  return parseConfig(R"({"name": "resume", "resolution": [48, 32], "grid": 4, "fps": 10, "warmup_frames": 0,
                         "max_frames": 3, )" +
                         body + "}",
                     "resume.json", baseDir);
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Sha256, MatchesTheFipsTestVectors) {
  EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256Hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256Hex(std::string(1000000, 'a')), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// Defect: the terrain label ignored extent, so two terrains differing only in extent
// gave one case id, the second was "resumed" from the first and vanished while run.json said ok.
TEST(CaseIdentity, TerrainsDifferingOnlyInExtentGetDistinctIdsAndBothRun) {
  Config c = config(R"("terrains": [{"type": "procedural", "size": 33, "seed": 5, "extent": 1000},
                                    {"type": "procedural", "size": 33, "seed": 5, "extent": 2000}],
                       "paths": ["paths/flyover.csv"], "schemes": ["sphere"])");
  std::vector<Case> cases = expandCases(c);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_NE(cases[0].id, cases[1].id);
  EXPECT_NE(cases[0].terrainLabel, cases[1].terrainLabel);
  EXPECT_NE(cases[0].digest, cases[1].digest);
  EXPECT_EQ(cases[0].id.rfind("sphere_proc33s5-", 0), 0u) << cases[0].id;  // still readable
  fs::path d = fresh("extent");
  RunTotals t = runSweep(c, {d.string(), false, false});
  EXPECT_EQ(t.ok, 2);
  EXPECT_EQ(t.resumed, 0);
  EXPECT_EQ(readCaseFiles(d.string()).size(), 2u);
  EXPECT_EQ(readRunJson(d.string())["totals"]["cases"], 2);
}

// Paths with one stem in two folders: the readable parts coincide, the contents differ.
TEST(CaseIdentity, SameStemDifferentContentsGetADigestSuffix) {
  fs::path d = fresh("stems");
  fs::create_directories(d / "a");
  fs::create_directories(d / "b");
  fs::copy_file(kConfigs + "/paths/flyover.csv", d / "a/p.csv");
  fs::copy_file(kConfigs + "/paths/lowalt.csv", d / "b/p.csv");
  Config c = config(R"("terrain": {"type": "procedural", "size": 33, "seed": 5},
                       "paths": ["a/p.csv", "b/p.csv"], "schemes": ["sphere"])",
                    d.string());
  std::vector<Case> cases = expandCases(c);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_NE(cases[0].id, cases[1].id);
  EXPECT_EQ(cases[0].id, "sphere_proc33s5_p_48x32_" + cases[0].digest.substr(0, 8));
}

TEST(CaseIdentity, DigestCoversFileContentsAndSettings) {
  fs::path d = fresh("digest");
  fs::copy_file(kConfigs + "/paths/flyover.csv", d / "p.csv");
  std::string body = R"("terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["p.csv"],
                        "schemes": [{"name": "uniform", "params": {"level": 3}}])";
  std::string before = expandCases(config(body, d.string()))[0].digest;
  EXPECT_EQ(expandCases(config(body, d.string()))[0].digest, before);  // stable
  std::ofstream(d / "p.csv", std::ios::app) << "# a comment changes the bytes\n";
  Case after = expandCases(config(body, d.string()))[0];
  EXPECT_NE(after.digest, before);
  EXPECT_EQ(after.id, "uniform-level3_proc33s5_p_48x32");  // the readable id stays
  Config other = config(body, d.string());
  other.measure.every = 2;
  EXPECT_NE(expandCases(other)[0].digest, after.digest);
}

TEST(CaseIdentity, DuplicateEntriesAreErrorsNamingBoth) {
  std::string e = errorOf([] {
    expandCases(config(R"("terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
                         "schemes": [{"name": "uniform", "params": {"level": 3}}, "sphere",
                                     {"name": "uniform", "params": {"level": [2, 3]}}])"));
  });
  // At the second entry's line and field, naming the first's line.
  EXPECT_NE(e.find("resume.json:4: field '/schemes/2': /schemes/0 (line 3) and /schemes/2 both run uniform level=3"),
            std::string::npos)
      << e;
  e = errorOf([] {
    expandCases(config(R"("terrains": [{"type": "procedural", "size": 33, "seed": 5},
                                       {"type": "procedural", "size": 33, "seed": 5}],
                         "paths": ["paths/flyover.csv"], "schemes": ["sphere"])"));
  });
  EXPECT_NE(e.find("resume.json:3: field '/terrains/1': terrain #1 (proc33s5; /terrains/0, line 2) and #2 (proc33s5) "
                   "are the same"),
            std::string::npos)
      << e;
  e = errorOf([] {
    expandCases(config(R"("terrain": {"type": "procedural", "size": 33, "seed": 5},
                         "paths": ["paths/flyover.csv", "paths/../paths/flyover.csv"], "schemes": ["sphere"])"));
  });
  EXPECT_NE(e.find("resume.json:3: field '/paths/1': camera path #1"), std::string::npos) << e;
  EXPECT_NE(e.find("/paths/0, line 3) and #2"), std::string::npos) << e;
  // A default listed beside the same parameters left out, and one value twice in one entry.
  e = errorOf([] {
    expandCases(config(R"("terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
                         "schemes": ["cdlod",
                                     {"name": "cdlod", "params": {"morph": 0.3}}])"));
  });
  EXPECT_NE(e.find("resume.json:4: field '/schemes/1': /schemes/0 (line 3) and /schemes/1 both run cdlod (defaults) "
                   "(also listed as morph=0.3); remove one"),
            std::string::npos)
      << e;
  e = errorOf([] {
    expandCases(config(R"("terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
                         "schemes": [{"name": "uniform", "params": {"level": [3, 3.0]}}])"));
  });
  EXPECT_NE(e.find("resume.json:3: field '/schemes/0': /schemes/0 lists twice: uniform level=3; remove one"),
            std::string::npos)
      << e;
}

// Defect: resume compared only the config JSON, so an edited path CSV left one run
// holding cases of two different paths.
TEST(Resume, ChangedPathCsvIsRefusedUnlessRerunChanged) {
  fs::path d = fresh("changed_path");
  fs::copy_file(kConfigs + "/paths/flyover.csv", d / "p.csv");
  std::string body = R"("terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["p.csv"],
                        "schemes": [{"name": "uniform", "params": {"level": 3}}, "sphere"])";
  fs::path run = d / "run";
  EXPECT_EQ(runSweep(config(body, d.string()), {run.string(), false, false}).ok, 2);
  std::string kept = slurp(run / "cases/sphere_proc33s5_p_48x32.json");
  std::ofstream(d / "p.csv", std::ios::app) << "20,0.5,0.3,0.5,0.6,0.05,0.6,60\n";
  std::string e = errorOf([&] { runSweep(config(body, d.string()), {run.string(), false, false}); });
  EXPECT_NE(e.find("2 finished case(s) were run with other inputs"), std::string::npos) << e;
  EXPECT_NE(e.find("sphere_proc33s5_p_48x32: path file contents (sha256"), std::string::npos) << e;
  EXPECT_NE(e.find("--rerun-changed"), std::string::npos) << e;
  EXPECT_EQ(slurp(run / "cases/sphere_proc33s5_p_48x32.json"), kept) << "a refused resume writes nothing";

  RunOptions o{run.string(), false, false};
  o.rerunChanged = true;
  RunTotals t = runSweep(config(body, d.string()), o);
  EXPECT_EQ(t.resumed, 0);
  EXPECT_EQ(t.ok, 2);
  Case now = expandCases(config(body, d.string()))[1];
  EXPECT_EQ(readJsonFile((run / "cases/sphere_proc33s5_p_48x32.json").string())["digest"], now.digest);
  // Unchanged now: the next resume keeps both.
  EXPECT_EQ(runSweep(config(body, d.string()), {run.string(), false, false}).resumed, 2);
}

// Defect: resuming a shard folder with another --shard mixed shards.
TEST(Resume, ShardMustMatchTheFolders) {
  fs::path d = fresh("shard");
  std::string body = R"("terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
                        "schemes": [{"name": "uniform", "params": {"level": [2, 3]}}, "sphere"])";
  fs::path run = d / "run";
  RunTotals t = runSweep(config(body), {run.string(), false, false, 0, 2});
  EXPECT_EQ(t.ok, 2);
  std::string e = errorOf([&] { runSweep(config(body), {run.string(), false, false, 1, 2}); });
  EXPECT_NE(e.find("holds shard 0/2, not 1/2"), std::string::npos) << e;
  e = errorOf([&] { runSweep(config(body), {run.string(), false, false}); });
  EXPECT_NE(e.find("holds shard 0/2, not 0/1"), std::string::npos) << e;
  json r = readRunJson(run.string());
  EXPECT_EQ(r["case_ids"].size(), readCaseFiles(run.string()).size());  // run.json describes the folder
}

// A case file of no case of the config (a scheme removed from it) is stale: kept and named, never
// refused or deleted (tests/test_grow_sweep.cpp); an unreadable one is an error naming it.
TEST(Resume, ForeignCaseFileIsStaleAndUnreadableOneNamed) {
  fs::path d = fresh("foreign");
  std::string body = R"("terrain": {"type": "procedural", "size": 33, "seed": 5}, "paths": ["paths/flyover.csv"],
                        "schemes": ["sphere"])";
  fs::path run = d / "run";
  runSweep(config(body), {run.string(), false, false});
  std::ofstream(run / "cases/other.json") << R"({"case_id": "other", "status": "ok", "frames": []})";
  EXPECT_EQ(runSweep(config(body), {run.string(), false, false}).resumed, 1);
  EXPECT_EQ(readRunJson(run.string())["stale_cases"], json::array({"other"}));
  EXPECT_TRUE(fs::exists(run / "cases/other.json"));
  std::ofstream(run / "cases/other.json") << "{\"case_id\": ";
  std::string e = errorOf([&] { writeAggregates(run.string(), json::object()); });
  EXPECT_NE(e.find((run / "cases/other.json").string() + ": not valid JSON"), std::string::npos) << e;
}

// SIGKILL at 20 moments drawn from a fixed seed; each invocation resumes the last. The result must
// equal an uninterrupted run counter for counter, and every kill later than 1 s into its
// invocation (more where start-up is slower, see below) must find more finished cases than the
// invocation started with.
TEST(Resume, SweepKilledAtTwentyRandomMomentsEqualsAnUninterruptedRun) {
  fs::path d = fresh("kill20");
  std::string cfg = (d / "kill.json").string();
  std::ofstream(cfg) << R"({"name": "kill20", "resolution": [96, 54], "grid": 8, "fps": 30, "warmup_frames": 1,
    "max_frames": 12, "terrain": {"type": "procedural", "size": 65, "seed": 2},
    "paths": [")" + kConfigs +
                            R"(/paths/flyover.csv", ")" + kConfigs + R"(/paths/lowalt.csv", ")" + kConfigs +
                            R"(/paths/horizon.csv"],
    "measure": {"every": 6, "passes": ["histogram", "popping"]},
    "schemes": [{"name": "uniform", "params": {"level": [2, 3, 4, 5, 6, 7, 8]}},
                {"name": "sphere", "params": {"tri_size": [2, 3, 4, 6, 8, 12, 16]}}]})";
  auto start = [&](const fs::path& out) {
    pid_t pid = fork();
    if (pid == 0) {
      unsetenv("LODBENCH_VALIDATION");  // lavapipe speed, not validation, is what kills race here
      int log = open((d / "log.txt").c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);  // read it when this fails
      dup2(log, 1);
      dup2(log, 2);
      execl(LODBENCH_BINARY, LODBENCH_BINARY, "run", cfg.c_str(), "--out", out.c_str(), "-q", (char*)nullptr);
      _exit(127);
    }
    return pid;
  };
  auto finished = [](const fs::path& run) {
    size_t n = 0;
    if (fs::exists(run / "cases"))
      for (auto& e : fs::directory_iterator(run / "cases")) n += e.path().extension() == ".json";
    return n;
  };
  fs::path ref = d / "ref", run = d / "run";
  int status = 0;
  // The uninterrupted run, timing its first finished case: on a loaded machine (ctest -j2 beside
  // other jobs) start-up plus one case (lavapipe compiles each case's pipelines) can pass a
  // second, so "a kill after the first second must find progress" uses the larger of 1 s and
  // 2 x (time to the first case + the slowest case) of this run.
  pid_t refPid = start(ref);
  auto r0 = std::chrono::steady_clock::now();
  double firstCase = 0;
  while (waitpid(refPid, &status, WNOHANG) != refPid) {
    if (firstCase == 0 && finished(ref) > 0)
      firstCase = std::chrono::duration<double>(std::chrono::steady_clock::now() - r0).count();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status << "\n" << slurp(d / "log.txt");
  double slowest = 0;
  for (auto& cf : readCaseFiles(ref.string())) slowest = std::max(slowest, cf.doc["seconds"].get<double>());
  const double progressAfter = std::max(1.0, 2.0 * (firstCase + slowest));
  std::printf("    first case after %.2f s, slowest case %.2f s: kills later than %.2f s must find progress\n",
              firstCase, slowest, progressAfter);
  const size_t total = finished(ref);
  ASSERT_EQ(total, 42u);

  // Counter for counter: every field of every frame record but the clocks.
  auto strip = [](json c) {
    for (auto& f : c["frames"])
      for (const char* k : {"gpu_ms", "cpu_ms", "cpu_harness_ms", "fps"}) f.erase(k);
    json s = c["summary"];
    for (const char* k : {"gpu_ms", "cpu_ms", "cpu_harness_ms", "fps_median", "fps_mean"}) s.erase(k);
    // The process's resident peak is measured like a clock: the allocator's history moves it.
    if (s.contains("memory") && s["memory"].is_object()) s["memory"].erase("host_peak_bytes");
    c["summary"] = s;
    c.erase("seconds");
    c.erase("measure_costs_ms");
    return c;
  };
  int compared = 0;
  auto expectEqualToRef = [&] {
    ++compared;
    auto a = readCaseFiles(ref.string()), b = readCaseFiles(run.string());
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].id(), b[i].id());
      EXPECT_EQ(b[i].doc["status"], "ok");
      EXPECT_EQ(strip(a[i].doc), strip(b[i].doc)) << a[i].id();
    }
    json ra = readRunJson(ref.string()), rb = readRunJson(run.string());
    EXPECT_EQ(ra["case_ids"], rb["case_ids"]);
    EXPECT_EQ(rb["totals"]["ok"], int(total));
    EXPECT_EQ(readJsonFile((run / "summary.json").string())["cases"].size(), total);
    for (auto& e : fs::recursive_directory_iterator(run))
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  };

  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> moment(0.05, 3.5);
  int kills = 0, lateKills = 0;
  // A sweep that finishes before its moment counts no kill and starts over, so on a fast machine
  // many attempts end that way (19 kills in 60 attempts once): the cap only stops a runaway loop.
  for (int attempt = 0; kills < 20 && attempt < 200; ++attempt) {
    size_t before = finished(run);
    double at = moment(rng);
    pid_t pid = start(run);
    auto t0 = std::chrono::steady_clock::now();
    bool exited = false;
    while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < at)
      if (waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;
        break;
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
    if (exited) {  // the sweep finished before the moment: check it, then start a new one
      ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status << "\n" << slurp(d / "log.txt");
      expectEqualToRef();
      fs::remove_all(run);
      continue;
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    ++kills;
    if (at > progressAfter) {
      ++lateKills;
      EXPECT_GT(finished(run), before) << "kill " << kills << " at " << at << " s made no progress";
    }
  }
  EXPECT_EQ(kills, 20);
  if (progressAfter < 3.0) EXPECT_GT(lateKills, 0);
  std::printf("    %d kills, %d after %.2f s\n", kills, lateKills, progressAfter);
  waitpid(start(run), &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "status " << status << "\n" << slurp(d / "log.txt");
  expectEqualToRef();
  EXPECT_GE(compared, 1);
}
