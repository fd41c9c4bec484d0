// The reference sides' table (contact/side_table.hpp): two bits a side give back every value
// (+1, −1, 0, no_side) at every place in a byte, and copies share a table until one of them
// takes other values — the other copy keeps its own.
#include <gtest/gtest.h>

#include <vector>

#include "tsmframe/contact/side_table.hpp"

using tsm::contact::no_side;
using tsm::contact::SideTable;

TEST(SideTable, GivesBackEverySideAtEveryPlace) {
  std::vector<signed char> sides;
  const signed char each[] = {1, -1, 0, no_side};
  for (int k = 0; k < 23; ++k) sides.push_back(each[(k * 7 + k / 4) % 4]);  // every value at every place in a byte
  SideTable table;
  EXPECT_EQ(table.size(), 0u);
  table.set(sides);
  ASSERT_EQ(table.size(), sides.size());
  for (size_t k = 0; k < sides.size(); ++k) EXPECT_EQ(table[k], sides[k]) << k;
  EXPECT_EQ(table.values(), sides);
}

TEST(SideTable, CopiesKeepTheirOwnSidesWhenOneChanges) {
  const std::vector<signed char> before = {1, 1, no_side, -1, 0}, after = {1, -1, no_side, -1, 0};
  SideTable state;
  state.set(before);
  SideTable kept = state;  // the step's start
  state.set(before);       // the same again: still one table
  state.set(after);
  EXPECT_EQ(state.values(), after);
  EXPECT_EQ(kept.values(), before);
  kept.set(std::vector<signed char>(3, no_side));  // another size
  EXPECT_EQ(kept.values(), std::vector<signed char>(3, no_side));
  EXPECT_EQ(state.values(), after);
}
