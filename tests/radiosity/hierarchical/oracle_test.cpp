// The oracle's split-or-keep rule, written once for plain pairs, links
// re-examined and pairs through mirrors, on charges and visibilities
// chosen to sit either side of each threshold.
#include <gtest/gtest.h>

#include "radiosity/hierarchical/oracle.h"

namespace bounce {
namespace {

constexpr double tolerance = 1.0, partial_factor = 4.0;

// The rule with a fixed visibility; `asked` counts the rays asked for.
pair_decision rule(double split, double bf, bool splittable, float visibility, bool dark_is_partial, int& asked) {
  return decide({bf, split}, splittable, tolerance, partial_factor, dark_is_partial, [&] {
    ++asked;
    return visibility;
  });
}

TEST(Oracle, PairsCarryingTooMuchAreSplitBeforeAnyRayIsCast) {
  int asked = 0;
  EXPECT_EQ(rule(1.5, 1.5, true, 1.0f, false, asked).verdict, pair_verdict::split);
  EXPECT_EQ(asked, 0);
  // Two leaves, or past the link limit: nothing can be split.
  const pair_decision kept = rule(1.5, 1.5, false, 1.0f, false, asked);
  EXPECT_EQ(kept.verdict, pair_verdict::keep);
  EXPECT_EQ(kept.visibility, 1.0f);
  EXPECT_EQ(asked, 1);
}

TEST(Oracle, PartlyVisiblePairsMustCarryPartialFactorTimesLess) {
  int asked = 0;
  // Charged 0.3 of the tolerance: kept when fully visible, split when
  // partly (4 x 0.3 > 1), kept when 0.2 (4 x 0.2 < 1).
  EXPECT_EQ(rule(0.3, 0.3, true, 1.0f, false, asked).verdict, pair_verdict::keep);
  EXPECT_EQ(rule(0.3, 0.3, true, 0.5f, false, asked).verdict, pair_verdict::split);
  EXPECT_EQ(rule(0.2, 0.2, true, 0.5f, false, asked).verdict, pair_verdict::keep);
  // The partial rule goes by F x B x A even where the split charge is lower
  // (a piece receiver whose form factor hardly varies).
  EXPECT_EQ(rule(0.0, 0.3, true, 0.5f, false, asked).verdict, pair_verdict::split);
  EXPECT_EQ(asked, 4);
}

TEST(Oracle, ADarkPairCountsAsPartlyVisibleOnlyThroughMirrors) {
  int asked = 0;
  const pair_decision plain = rule(0.3, 0.3, true, 0.0f, false, asked);
  EXPECT_EQ(plain.verdict, pair_verdict::keep);  // a plain pair in full shadow
  EXPECT_EQ(plain.visibility, 0.0f);
  EXPECT_EQ(rule(0.3, 0.3, true, 0.0f, true, asked).verdict, pair_verdict::split);  // through a mirror
  EXPECT_EQ(rule(0.2, 0.2, true, 0.0f, true, asked).verdict, pair_verdict::keep);
}

}  // namespace
}  // namespace bounce
