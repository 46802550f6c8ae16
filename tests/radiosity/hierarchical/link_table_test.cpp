// The link table's index: links sorted by receiver (then chain, then
// source), and every node's links found from its offsets.
#include <gtest/gtest.h>

#include "radiosity/hierarchical/link_table.h"

namespace bounce {
namespace {

TEST(LinkTable, IndexSortsByReceiverAndGivesEveryNodeItsLinks) {
  link_table<hierarchy_link> table;
  table.links = {{3, 1, 0.1f, 1.0f}, {0, 2, 0.2f, 1.0f}, {3, 0, 0.3f, 0.5f}, {1, 3, 0.4f, 1.0f}};
  index_links(table, 5);
  ASSERT_EQ(table.offsets.size(), 6u);
  EXPECT_EQ(table.count_of(0), 1u);
  EXPECT_EQ(table.count_of(1), 1u);
  EXPECT_EQ(table.count_of(2), 0u);
  EXPECT_EQ(table.count_of(3), 2u);
  EXPECT_EQ(table.count_of(4), 0u);
  ASSERT_EQ(table.of(3).size(), 2u);
  EXPECT_EQ(table.of(3)[0].source, 0);  // then by source
  EXPECT_EQ(table.of(3)[1].source, 1);
  EXPECT_FLOAT_EQ(table.of(0)[0].factor, 0.2f);
}

TEST(LinkTable, MirrorLinksSortByChainBeforeSource) {
  link_table<mirror_link> table;
  table.links = {{{2, 0, 0.1f, 1.0f}, 1}, {{2, 1, 0.2f, 1.0f}, 0}, {{0, 1, 0.3f, 1.0f}, 1}};
  index_links(table, 3);
  ASSERT_EQ(table.count_of(2), 2u);
  EXPECT_EQ(table.of(2)[0].chain, 0);
  EXPECT_EQ(table.of(2)[1].chain, 1);
}

TEST(LinkTable, RenumberingFollowsTheExtendedTree) {
  link_table<hierarchy_link> table;
  table.links = {{0, 1, 0.5f, 1.0f}, {1, 0, 0.5f, 1.0f}};
  const int node_of_old[] = {4, 7};
  renumber_links(table, node_of_old);
  index_links(table, 8);
  EXPECT_EQ(table.count_of(4), 1u);
  EXPECT_EQ(table.of(4)[0].source, 7);
  EXPECT_EQ(table.of(7)[0].source, 4);
}

}  // namespace
}  // namespace bounce
