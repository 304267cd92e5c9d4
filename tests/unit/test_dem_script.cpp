// DEM scripts as the coupler runs them: parsing, the coupled-script checks, the restart rewrite.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "tfdem/dem_script.h"

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

TEST(DemScript, ParsesCommentsContinuationsAndQuotes) {
  const auto commands = parse(kScript);
  ASSERT_EQ(commands.size(), 6u);
  EXPECT_EQ(commands[1].line, 3);
  EXPECT_EQ(commands[1].words, (std::vector<std::string>{"read_data", "bed.data"}));
  EXPECT_EQ(commands[2].line, 4);
  EXPECT_EQ(commands[2].line_count, 2);
  EXPECT_EQ(commands[2].words.back(), "history");
  EXPECT_EQ(commands[4].words[5], "\"${t} # not a comment\"");
}

TEST(DemScript, CoupledScriptPassesAsItIs) { EXPECT_TRUE(coupled_script_problems("in.bed", parse(kScript)).empty()); }

TEST(DemScript, RunClearAndCouplingFixCountAreProblems) {
  const auto problems =
      coupled_script_problems("in.bed", parse("fix a all tfdem/coupling\nrun 100\nclear\nfix b all tfdem/coupling\n"));
  ASSERT_EQ(problems.size(), 3u);
  EXPECT_NE(problems[0].find("in.bed:2: 'run'"), std::string::npos);
  EXPECT_NE(problems[1].find("in.bed:3: 'clear'"), std::string::npos);
  EXPECT_NE(problems[2].find("2 'fix ... tfdem/coupling' (lines 1, 4)"), std::string::npos);
  const auto none = coupled_script_problems("in.bed", parse("atom_style granular\n"));
  ASSERT_EQ(none.size(), 1u);
  EXPECT_NE(none[0].find("no 'fix ID all tfdem/coupling'"), std::string::npos);
}

TEST(DemScript, ResumedScriptReadsTheRestartAndAppendsOutputs) {
  const std::string resumed = resumed_script("in.bed", kScript, "0.5/dem.restart");
  const auto commands = parse(resumed);
  ASSERT_EQ(commands.size(), 7u);
  EXPECT_EQ(commands[1].line, 3);  // line numbers kept for LIGGGHTS' messages
  EXPECT_EQ(commands[1].words, (std::vector<std::string>{"read_restart", "0.5/dem.restart"}));
  EXPECT_EQ(commands[4].line, 7);
  EXPECT_EQ(commands[4].words[6], "append");
  EXPECT_EQ(commands[4].words[7], "height.txt");
  EXPECT_EQ(commands[6].words, (std::vector<std::string>{"dump_modify", "snap", "append", "yes"}));
}

TEST(DemScript, ResumingNeedsExactlyOneReadData) {
  EXPECT_THROW(resumed_script("in.bed", "create_box 1 box\n", "r"), std::invalid_argument);
  EXPECT_THROW(resumed_script("in.bed", "read_data a\nread_data b\n", "r"), std::invalid_argument);
}

}  // namespace
