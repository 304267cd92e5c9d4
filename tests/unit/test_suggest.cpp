#include <gtest/gtest.h>

#include "tfdem/suggest.h"

namespace {

TEST(Suggest, EditDistanceCountsSingleEdits) {
  EXPECT_EQ(tfdem::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(tfdem::edit_distance("", "abc"), 3u);
  EXPECT_EQ(tfdem::edit_distance("same", "same"), 0u);
}

TEST(Suggest, NearestNameFindsTyposButNotUnrelatedWords) {
  const std::vector<std::string> valid = {"weight_fraction", "gravity"};
  EXPECT_EQ(tfdem::nearest_name("wieght_fraction", valid), "weight_fraction");
  EXPECT_EQ(tfdem::nearest_name("gravty", valid), "gravity");
  EXPECT_EQ(tfdem::nearest_name("xyz", valid), "");
  EXPECT_EQ(tfdem::did_you_mean("xyz", valid), "");
  EXPECT_EQ(tfdem::did_you_mean("gravty", valid), " (did you mean 'gravity'?)");
  EXPECT_EQ(tfdem::quoted_list(valid), "'weight_fraction', 'gravity'");
}

}  // namespace
