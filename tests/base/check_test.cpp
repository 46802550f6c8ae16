// The policy for programmer errors: BOUNCE_CHECK stops the program in every
// build; BOUNCE_DCHECK only where assertions are on (no NDEBUG).
#include <gtest/gtest.h>

#include "base/check.h"

namespace bounce {
namespace {

TEST(Check, AFailedCheckStopsNamingTheCondition) {
  const int two = 2;
  EXPECT_DEATH(BOUNCE_CHECK(two + two == 5), "internal error: check failed: two \\+ two == 5");
  BOUNCE_CHECK(two + two == 4);  // a check that holds does nothing
}

TEST(Check, AFailedComparisonPrintsBothSides) {
  const int count = 3;
  const std::size_t size = 7;
  const double area = 0.25;
  EXPECT_DEATH(BOUNCE_CHECK_LT(count + 5, 6), "check failed: count \\+ 5 < 6 \\(8 vs 6\\)");
  EXPECT_DEATH(BOUNCE_CHECK_EQ(size, std::size_t(9)), "check failed: size == std::size_t\\(9\\) \\(7 vs 9\\)");
  EXPECT_DEATH(BOUNCE_CHECK_GT(area, 0.5), "\\(0.25 vs 0.5\\)");
  // Each side is evaluated once, failing or not.
  int calls = 0;
  auto next = [&] { return ++calls; };
  BOUNCE_CHECK_LE(next(), 1);
  BOUNCE_CHECK_GE(next(), 2);
  BOUNCE_CHECK_NE(next(), 4);
  EXPECT_EQ(calls, 3);
}

TEST(Check, DebugChecksFollowTheAssertions) {
  int evaluated = 0;
  auto holds = [&] {
    ++evaluated;
    return false;
  };
#ifdef NDEBUG
  BOUNCE_DCHECK(holds());
  EXPECT_EQ(evaluated, 0);         // not even evaluated
  BOUNCE_DCHECK_EQ(evaluated, 1);  // compiled, never run
#else
  EXPECT_DEATH(BOUNCE_DCHECK(holds()), "check failed: holds\\(\\)");
  EXPECT_DEATH(BOUNCE_DCHECK_EQ(evaluated, 1), "\\(0 vs 1\\)");
#endif
}

}  // namespace
}  // namespace bounce
