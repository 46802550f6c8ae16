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

TEST(Check, DebugChecksFollowTheAssertions) {
  int evaluated = 0;
  auto holds = [&] {
    ++evaluated;
    return false;
  };
#ifdef NDEBUG
  BOUNCE_DCHECK(holds());
  EXPECT_EQ(evaluated, 0);  // not even evaluated
#else
  EXPECT_DEATH(BOUNCE_DCHECK(holds()), "check failed: holds\\(\\)");
#endif
}

}  // namespace
}  // namespace bounce
