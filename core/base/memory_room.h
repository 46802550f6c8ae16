// How much memory this process may still take, asked before a large
// allocation so that a scene too large for the machine is refused with
// figures instead of ending in std::bad_alloc, or in the kernel's
// out-of-memory killer, which ends a process without a word.
#pragma once

#include <string>

namespace bounce {

struct memory_room {
  double bytes = 0.0;  // may be infinite
  std::string bound;   // what bounds it, in words
};

// The smaller of the address-space limit (RLIMIT_AS, `ulimit -v`) less
// what the process has mapped, and the machine's physical memory.
memory_room available_memory();

// "512 MB", "2.1 GB": decimal units, three significant figures at most.
std::string format_bytes(double bytes);

}  // namespace bounce
