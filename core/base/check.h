// Programmer errors: invariants that no input, however bad, can break. Bad
// input gets an error message with its file and line (scene_io.h); a
// failed check is a bug in Bounce, and stops the program with the
// condition, the file and the line.
//
// BOUNCE_CHECK is on in every build: for cheap checks (O(1) per call, or
// small next to the work around them). BOUNCE_DCHECK is on where
// assertions are (builds without NDEBUG: the sanitizer preset that CI
// runs): for checks that cost time.
#pragma once

namespace bounce {

[[noreturn]] void check_failed(const char* condition, const char* file, int line);

}  // namespace bounce

#define BOUNCE_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::bounce::check_failed(#condition, __FILE__, __LINE__))

#ifdef NDEBUG
#define BOUNCE_DCHECK(condition) static_cast<void>(sizeof(static_cast<bool>(condition)))
#else
#define BOUNCE_DCHECK(condition) BOUNCE_CHECK(condition)
#endif
