// Warnings grouped by what they say: counts, first and last place, order.
#include "scene/warning_groups.h"

#include <gtest/gtest.h>

namespace bounce {
namespace {

TEST(WarningGroups, ManyOfAKindBecomeOneLineWithTheirCount) {
  std::vector<std::string> warnings;
  for (int line = 10; line < 11173; ++line)
    warnings.push_back("engine.obj:" + std::to_string(line) + ": degenerate face (zero area) dropped");
  warnings.insert(warnings.begin() + 5, "engine.mtl:3: 'Ks' is not used by Bounce; ignored");
  warnings.push_back("engine.obj: surface 'lamp' emits (material 'glow') but faces nothing it could light");
  const std::vector<warning_group> groups = group_warnings(warnings);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].text, "degenerate face (zero area) dropped");
  EXPECT_EQ(groups[0].count, 11163u);
  EXPECT_EQ(groups[0].first_at, "engine.obj:10");
  EXPECT_EQ(groups[0].last_at, "engine.obj:11172");
  EXPECT_EQ(describe(groups[0]),
            "degenerate face (zero area) dropped: 11163 times (first at engine.obj:10, last at engine.obj:11172)");
  // A warning alone reads as it was written.
  EXPECT_EQ(describe(groups[1]), "engine.mtl:3: 'Ks' is not used by Bounce; ignored");
  EXPECT_EQ(groups[2].first_at, "engine.obj");
  EXPECT_EQ(describe(groups[2]), warnings.back());
}

TEST(WarningGroups, AWarningWithoutAPlaceStaysWhole) {
  const std::vector<warning_group> groups = group_warnings({"no place here", "no place here"});
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0].count, 2u);
  EXPECT_EQ(describe(groups[0]), "no place here: 2 times");
  EXPECT_TRUE(group_warnings({}).empty());
}

}  // namespace
}  // namespace bounce
