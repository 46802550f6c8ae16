// Loops over index ranges in blocks: on TBB's threads, or serially when a
// caller turns parallelism off (determinism checks, nested use).
#pragma once

#include <cstddef>

#include <tbb/parallel_for.h>

namespace bounce {

// Calls body(begin, end) for blocks covering [0, count), about `grain`
// indices each.
template <typename block_body>
void for_each_block(bool parallel, std::size_t count, std::size_t grain, block_body&& body) {
  if (!parallel) {
    body(std::size_t(0), count);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

}  // namespace bounce
