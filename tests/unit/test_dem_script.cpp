// DEM scripts as the coupler runs them: parsing, includes, the coupled-script checks, the
// output files and the restart rewrite, on hand-written scripts.
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>
#include <string>

#include "dem_script.h"

namespace {

using namespace tfdem::dem_script;

const std::string kScript =
    "# a coupled bed\n"
    "atom_style granular\n"
    "read_data bed.data   # the packed bed\n"
    "pair_style gran model hooke/stiffness &\n"
    "    tangential history\n"
    "fix fluid all tfdem/coupling\n"
    "fix out all print 100 \"${t} # not a comment\" file height.txt screen no\n"
    "dump snap all custom 1000 p.dump id x y\n";

// Files by name, as a case would hold them; a missing one throws as reading it would.
ReadFile files(std::map<std::string, std::string> texts) {
  return [texts](const std::string &path) {
    const auto found = texts.find(path);
    if (found == texts.end()) throw std::runtime_error("cannot read '" + path + "': No such file or directory");
    return found->second;
  };
}

bool has(const std::vector<std::string> &problems, const std::string &text) {
  for (const auto &p : problems)
    if (p.find(text) != std::string::npos) return true;
  return false;
}

TEST(DemScript, ParsesCommentsContinuationsAndQuotes) {
  const auto commands = parse(kScript, "in.bed");
  ASSERT_EQ(commands.size(), 6u);
  EXPECT_EQ(commands[1].line, 3);
  EXPECT_EQ(commands[1].where(), "in.bed:3: ");
  EXPECT_EQ(commands[1].words, (std::vector<std::string>{"read_data", "bed.data"}));
  EXPECT_EQ(commands[2].line, 4);
  EXPECT_EQ(commands[2].line_count, 2);
  EXPECT_EQ(commands[2].words.back(), "history");
  EXPECT_EQ(commands[4].words[5], "\"${t} # not a comment\"");
}

TEST(DemScript, CoupledScriptPassesAsItIs) {
  EXPECT_TRUE(coupled_script_problems("in.bed", load("in.bed", files({{"in.bed", kScript}}))).empty());
}

TEST(DemScript, RunClearJumpAndCouplingFixCountAreProblems) {
  const auto problems = coupled_script_problems(
      "in.bed", load("in.bed", files({{"in.bed", "fix a all tfdem/coupling\nrun 100\nclear\nfix b all tfdem/coupling\n"
                                                 "jump SELF again\n"}})));
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_NE(problems[0].find("in.bed:2: 'run'"), std::string::npos);
  EXPECT_NE(problems[1].find("in.bed:3: 'clear'"), std::string::npos);
  EXPECT_NE(problems[2].find("in.bed:5: 'jump'"), std::string::npos);
  EXPECT_NE(problems[3].find("2 'fix ... tfdem/coupling' (in.bed:1, in.bed:4)"), std::string::npos);
  const auto none = coupled_script_problems("in.bed", load("in.bed", files({{"in.bed", "atom_style granular\n"}})));
  ASSERT_EQ(none.size(), 1u);
  EXPECT_NE(none[0].find("no 'fix ID all tfdem/coupling'"), std::string::npos);
}

TEST(DemScript, IncludesAreFollowedInOrder) {
  const Script s = load("in.bed", files({{"in.bed", "atom_style granular\ninclude parts/walls.in\nfix f all nve\n"},
                                         {"parts/walls.in", "include coupling.in\nfix w all wall/gran\n"},
                                         {"coupling.in", "fix fluid all tfdem/coupling\nrun 10\n"}}));
  ASSERT_EQ(s.commands.size(), 5u);
  EXPECT_EQ(s.commands[1].where(), "coupling.in:1: ");
  EXPECT_EQ(s.commands[3].where(), "parts/walls.in:2: ");
  EXPECT_EQ(s.commands[4].where(), "in.bed:3: ");
  const auto problems = coupled_script_problems("in.bed", s);
  // the coupling fix in an included file counts; a run there is found
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("coupling.in:2: 'run'"), std::string::npos);
}

TEST(DemScript, IncludesThatCannotBeFollowedAreProblems) {
  const Script s = load("in.bed", files({{"in.bed", "include a.in\ninclude missing.in\ninclude ${part}.in\n"
                                                    "fix fluid all tfdem/coupling\n"},
                                         {"a.in", "include b.in\n"},
                                         {"b.in", "include a.in\n"}}));
  const auto problems = coupled_script_problems("in.bed", s);
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_TRUE(has(problems, "b.in:1: include 'a.in' includes itself (through in.bed a.in b.in)"));
  EXPECT_TRUE(has(problems, "in.bed:2: include 'missing.in': cannot read 'missing.in': No such file or directory"));
  EXPECT_TRUE(has(problems, "in.bed:3: include '${part}.in'"));
  // read alone (a pour's script, whose templates file a variable names), the variable
  // include is no problem: it stays a command, unfollowed; only the coupler refuses it
  ASSERT_EQ(s.problems.size(), 2u);
  const Command *kept = s.first("include");
  ASSERT_NE(kept, nullptr);
  EXPECT_EQ(kept->words[1], "${part}.in");
}

TEST(DemScript, OutputFilesWithLiteralNames) {
  std::vector<std::string> skipped;
  const Script s = load("in.bed", files({{"in.bed", kScript +
                                                        "fix avg all ave/time 1 5 200 c_f file forces.txt\n"
                                                        "fix log all print 50 \"x\" append log.txt\n"
                                                        "dump vtk all custom/vtk 100 post/p*.vtk id\n"
                                                        "fix v all print 10 \"y\" file ${name}.txt\n"}}));
  const auto out = output_files(s, &skipped);
  ASSERT_EQ(out.size(), 4u);
  EXPECT_EQ(out[0].kind, OutputFile::Kind::Print);
  EXPECT_EQ(out[0].path, "height.txt");
  EXPECT_EQ(out[0].every, 100);
  EXPECT_EQ(out[1].kind, OutputFile::Kind::Dump);
  EXPECT_EQ(out[1].path, "p.dump");
  EXPECT_EQ(out[1].id, "snap");
  EXPECT_EQ(out[1].every, 1000);
  EXPECT_EQ(out[2].kind, OutputFile::Kind::Average);
  EXPECT_EQ(out[2].path, "forces.txt");
  EXPECT_EQ(out[2].every, 1);
  EXPECT_EQ(out[2].repeat, 5);
  EXPECT_EQ(out[2].frequency, 200);
  EXPECT_EQ(out[3].path, "log.txt");
  EXPECT_EQ(out[3].where, "in.bed:10: ");
  EXPECT_EQ(skipped, (std::vector<std::string>{"in.bed:11: post/p*.vtk", "in.bed:12: ${name}.txt"}));
}

TEST(DemScript, ResumedScriptIsFlatReadsTheRestartAndAppendsDumps) {
  const Script s = load("in.bed", files({{"in.bed", "include setup.in\n" + kScript.substr(kScript.find("pair_style"))},
                                         {"setup.in", "atom_style granular\nread_data bed.data\n"}}));
  const auto commands = parse(resumed_script("in.bed", s, "0.5/dem.restart"));
  ASSERT_EQ(commands.size(), 7u);
  EXPECT_EQ(commands[1].words, (std::vector<std::string>{"read_restart", "0.5/dem.restart"}));
  EXPECT_EQ(commands[2].words.back(), "history");  // continuation joined
  EXPECT_EQ(commands[4].words[6], "file");  // fix print files are continued by the coupler
  EXPECT_EQ(commands[6].words, (std::vector<std::string>{"dump_modify", "snap", "append", "yes"}));
}

TEST(DemScript, ResumedScriptTakesCreatedParticlesFromTheRestart) {
  const Script s = load("in.settling", files({{"in.settling", "region box block 0 1 0 1 0 1\ncreate_box 1 box\n"
                                                              "create_atoms 1 single 0.5 0.5 0.5\n"
                                                              "set atom * diameter 1e-4 density 2500\n"
                                                              "velocity all set 0 0 0\nfix fluid all tfdem/coupling\n"}}));
  const auto commands = parse(resumed_script("in.settling", s, "0.1/dem.restart"));
  ASSERT_EQ(commands.size(), 3u);
  EXPECT_EQ(commands[0].words[0], "region");
  EXPECT_EQ(commands[1].words, (std::vector<std::string>{"read_restart", "0.1/dem.restart"}));
  EXPECT_EQ(commands[2].words[3], "tfdem/coupling");
}

TEST(DemScript, ResumingNeedsExactlyOneBox) {
  EXPECT_THROW(resumed_script("in.bed", load("in.bed", files({{"in.bed", "region b block 0 1 0 1 0 1\n"}})), "r"),
               std::invalid_argument);
  EXPECT_THROW(resumed_script("in.bed", load("in.bed", files({{"in.bed", "read_data a\ncreate_box 1 b\n"}})), "r"),
               std::invalid_argument);
  EXPECT_THROW(resumed_script("in.bed", load("in.bed", files({{"in.bed", "read_data a\nread_data b\n"}})), "r"),
               std::invalid_argument);
}

// processors_problem on hand-made scripts: the counts' product against the rank count.
TEST(DemScript, ProcessorCountsMustMatchTheRanks) {
  const auto problem = [](const std::string &grid, int ranks) {
    return processors_problem(load("in.bed", [&](const std::string &) {
      return "units si\nprocessors " + grid + "\nread_data bed.data\nfix cpl all tfdem/coupling\n";
    }), ranks);
  };
  EXPECT_EQ(problem("* 1 1", 3), "");
  EXPECT_EQ(problem("2 2 1", 4), "");
  EXPECT_EQ(problem("* 2 1", 6), "");
  EXPECT_EQ(problem("${px} 1 1", 3), "");
  EXPECT_EQ(problem("2 1 1 grid onelevel", 2), "");
  const std::string fixed = problem("2 1 1", 3);
  EXPECT_NE(fixed.find("in.bed:2: processors 2 1 1 asks for 2 ranks of the DEM on a run of 3 ranks"), std::string::npos) << fixed;
  EXPECT_NE(fixed.find("mpirun -np 2"), std::string::npos) << fixed;
  EXPECT_NE(fixed.find("'processors * 1 1'"), std::string::npos) << fixed;
  const std::string partly = problem("* 2 1", 3);
  EXPECT_NE(partly.find("fixes 2 ranks of the DEM on its given axes on a run of 3 ranks, which 2 does not divide"),
            std::string::npos) << partly;
  EXPECT_NE(problem("2 2 1", 1), "");
  const Script none = load("in.bed", [](const std::string &) { return "units si\n"; });
  EXPECT_EQ(processors_problem(none, 4), "");
}

}  // namespace
