// The README's commands work on a fresh clone: every command line of its ```sh blocks either runs
// here, against the built binary from the source folder, or says what else it needs with a
// trailing `# needs: <what>` (gpu, dem, long, cluster, gdal, setup). A command that is neither
// fails this test, so an example can no longer rot unnoticed.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.h"

namespace {

const std::string kSrc = LODBENCH_SOURCE_DIR;
const std::set<std::string> kNeeds = {"gpu", "dem", "long", "cluster", "gdal", "setup"};

struct Command {
  int line = 0;       // README line where it starts
  std::string text;   // continuation lines joined, without its comment
  std::string needs;  // the word after "# needs: ", "" when unmarked
};

std::string trim(const std::string& s) {
  size_t a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// Command lines of every ```sh block; comment-only lines are prose, not commands.
std::vector<Command> readmeCommands(const std::string& file) {
  std::ifstream in(file);
  std::vector<Command> out;
  bool inSh = false;
  std::string pending;
  int start = 0, n = 0;
  for (std::string line; std::getline(in, line);) {
    ++n;
    if (line.rfind("```", 0) == 0) {
      inSh = !inSh && line == "```sh";
      continue;
    }
    if (!inSh) continue;
    if (pending.empty()) start = n;
    if (!line.empty() && line.back() == '\\') {  // continued on the next line
      pending += line.substr(0, line.size() - 1) + " ";
      continue;
    }
    std::string whole = pending + line;
    pending.clear();
    if (trim(whole).empty() || trim(whole)[0] == '#') continue;
    Command c{start, whole, ""};
    size_t hash = whole.find(" #");
    if (hash != std::string::npos) {
      std::string comment = trim(whole.substr(hash + 2));
      c.text = whole.substr(0, hash);
      if (comment.rfind("needs: ", 0) == 0) {
        std::string word = comment.substr(7);
        c.needs = word.substr(0, word.find_first_of(" ;,(:"));
      }
    }
    c.text = trim(c.text);
    out.push_back(c);
  }
  return out;
}

// What is wrong with each command, "README.md:<line>: ..." (empty: every command ran or is marked);
// `ran` counts those run.
std::vector<std::string> problems(const std::string& file, int& ran) {
  std::vector<std::string> out;
  ran = 0;
  for (const Command& c : readmeCommands(file)) {
    const std::string at = file + ":" + std::to_string(c.line) + ": " + c.text + ": ";
    if (!c.needs.empty()) {
      if (!kNeeds.count(c.needs))
        out.push_back(at + "'# needs: " + c.needs + "' is not one of gpu, dem, long, cluster, gdal, setup");
      continue;
    }
    // Unmarked: it must be a lodbench command this test can run from the source folder, writing
    // nowhere but /tmp.
    const std::string prefix = "build/lodbench";
    if (c.text.rfind(prefix, 0) != 0) {
      out.push_back(at + "neither run by this test (not build/lodbench ...) nor marked '# needs: ...'");
      continue;
    }
    if (c.text.find_first_of("<>[]|$*") != std::string::npos) {
      out.push_back(at + "a synopsis, not a command: make it runnable or mark it '# needs: ...'");
      continue;
    }
    lb::test::CliOut o = lb::test::shell("cd '" + kSrc + "' && " + LODBENCH_BINARY + c.text.substr(prefix.size()));
    ++ran;
    if (o.code != 0) out.push_back(at + "exit " + std::to_string(o.code) + ":\n" + o.text);
  }
  return out;
}

}  // namespace

TEST(Readme, EveryCommandRunsHereOrSaysWhatItNeeds) {
  ASSERT_GT(readmeCommands(kSrc + "/README.md").size(), 10u) << "README.md's ```sh blocks were not found";
  int ran = 0;
  std::string report;
  for (const std::string& p : problems(kSrc + "/README.md", ran)) report += "\n" + p;
  EXPECT_TRUE(report.empty()) << report;
  EXPECT_GE(ran, 5) << "the quick commands (help, list, devices, dry-run, render, compare) run here";
}

// Planted: an unmarked script, a synopsis, an unknown marker and a failing command are each
// named; a runnable and a marked command are not.
TEST(Readme, CommandsNeitherRunNorMarkedAreNamed) {
  std::string f = ::testing::TempDir() + "/readme_planted.md";
  std::ofstream(f) << "```sh\nbuild/lodbench list\nbash scripts/test.sh\nbuild/lodbench run CONFIG [--out DIR]\n"
                      "build/lodbench render --path /nonexistent.csv --out /tmp/x.png\n"
                      "build/lodbench run configs/full.json   # needs: gpux\n"
                      "build/lodbench run configs/full.json   # needs: long (hours)\n```\n";
  int ran = 0;
  std::vector<std::string> p = problems(f, ran);
  ASSERT_EQ(p.size(), 4u);
  EXPECT_NE(p[0].find(":3: bash scripts/test.sh: neither run"), std::string::npos) << p[0];
  EXPECT_NE(p[1].find(":4: build/lodbench run CONFIG [--out DIR]: a synopsis"), std::string::npos) << p[1];
  EXPECT_NE(p[2].find(":5: build/lodbench render --path /nonexistent.csv --out /tmp/x.png: exit 2"), std::string::npos)
      << p[2];
  EXPECT_NE(p[3].find(":6: build/lodbench run configs/full.json: '# needs: gpux' is not one of"), std::string::npos)
      << p[3];
  EXPECT_EQ(ran, 2);
}

// The parser itself on a planted block: a marked, an unmarked and a continued command.
TEST(Readme, ParserJoinsContinuationsAndReadsMarkers) {
  std::string f = ::testing::TempDir() + "/readme_probe.md";
  std::ofstream(f) << "text\n```sh\n# a comment line\nbuild/lodbench list   # schemes\n"
                      "build/lodbench render \\\n    --frame 3   # needs: gpu (H100 figures)\n```\n"
                      "```json\n{\"not\": \"a command\"}\n```\n";
  std::vector<Command> c = readmeCommands(f);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].text, "build/lodbench list");
  EXPECT_EQ(c[0].needs, "");
  EXPECT_EQ(c[1].text, "build/lodbench render      --frame 3");
  EXPECT_EQ(c[1].needs, "gpu");
  EXPECT_EQ(c[1].line, 5);
}
