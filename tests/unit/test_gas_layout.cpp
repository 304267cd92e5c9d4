// The gas layout rule against the crossing worked by hand from its two measured step costs.
#include <gtest/gtest.h>

#include "tfdem/gas_layout.h"

namespace {

using namespace tfdem::gas_layout;

// Whole 0.63 ms + 3.8 us C, split 2.2 ms + 4.4 us C / N: they meet at
// C = 1.57 ms / (3.8 - 4.4 / N) us: 981.25 cells on 2 ranks, 581.48 on 4, 413.16 in the limit.
TEST(GasLayout, SplitPaysFromTheCrossingOfTheMeasuredCosts) {
  EXPECT_NEAR(split_from_cells(2), 1.57e-3 / 1.6e-6, 1e-9);
  EXPECT_NEAR(split_from_cells(4), 1.57e-3 / 2.7e-6, 1e-9);
  EXPECT_NEAR(split_from_cells(1000000), 1.57e-3 / 3.8e-6, 1e-3);
  EXPECT_LT(split_from_cells(1), 0.0);
}

TEST(GasLayout, TutorialsStayWholeBigMeshesSplit) {
  EXPECT_EQ(recommended(675, 2), Layout::whole);  // the tutorials' 15 x 45
  EXPECT_EQ(recommended(981, 2), Layout::whole);
  EXPECT_EQ(recommended(982, 2), Layout::split);
  EXPECT_EQ(recommended(675, 4), Layout::split);
  EXPECT_EQ(recommended(1e6, 1), Layout::whole);
}

TEST(GasLayout, AdviceNamesTheRuleAndTheFix) {
  const std::string agree = advice(675, 2, Layout::whole);
  EXPECT_NE(agree.find("675 cells on 2 ranks, the gas whole: as the measured rule has it (split from 981 cells"),
            std::string::npos) << agree;
  EXPECT_EQ(agree.find("Fix"), std::string::npos) << agree;
  const std::string differ = advice(43940, 2, Layout::whole);
  EXPECT_NE(differ.find("the measured rule would have it split"), std::string::npos) << differ;
  EXPECT_NE(differ.find("decomposePar (numberOfSubdomains 2), mpirun -np 2 tfdemFoam -parallel"), std::string::npos)
      << differ;
}

}  // namespace
