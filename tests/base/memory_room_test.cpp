// The memory a process may still take (memory_room.h), and the figures
// its messages print.
#include <cmath>

#include <gtest/gtest.h>

#include "base/memory_room.h"
#include "child_process.h"

namespace bounce {
namespace {

TEST(MemoryRoom, BytesAreWrittenInDecimalUnits) {
  EXPECT_EQ(format_bytes(999), "999 bytes");
  EXPECT_EQ(format_bytes(2000), "2 kB");
  EXPECT_EQ(format_bytes(512e6), "512 MB");
  EXPECT_EQ(format_bytes(2.064e9), "2.06 GB");
  EXPECT_EQ(format_bytes(INFINITY), "unlimited");
}

// Without a limit the room is the machine's memory; under `ulimit -v` (set
// in a child, so the tests keep theirs) it is the limit less what the
// process has mapped, and says so.
TEST(MemoryRoom, AnAddressSpaceLimitBoundsTheRoom) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer maps more address space than any such limit";
#endif
  const memory_room machine = available_memory();
  ASSERT_GT(machine.bytes, 0.0);
  EXPECT_TRUE(test_support::holds_under_limit(RLIMIT_AS, 6'000'000'000, [&] {
    const memory_room room = available_memory();
    // Bounded by the limit (the program maps far less than 2 GB), unless
    // the machine has less memory still.
    const bool by_limit = room.bytes <= 6e9 && room.bytes > 4e9 && room.bound.find("ulimit -v") != std::string::npos;
    const bool by_machine = machine.bytes < 4e9 && room.bytes == machine.bytes;
    return by_limit || by_machine;
  }));
}

}  // namespace
}  // namespace bounce
