// Checks that need a process limit of their own (an address-space limit,
// a file-size limit) run in a forked child, so the test process keeps its
// limits.
#pragma once

#include <functional>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace bounce::test_support {

// Runs `check` in a child whose soft limit on `resource` (RLIMIT_AS,
// RLIMIT_FSIZE, ...) is `soft`; true when it returned true there.
inline bool holds_under_limit(int resource, rlim_t soft, const std::function<bool()>& check) {
  const pid_t child = fork();
  if (child < 0) return false;
  if (child == 0) {
    rlimit limit{};
    getrlimit(resource, &limit);
    limit.rlim_cur = soft;
    if (setrlimit(resource, &limit) != 0) _exit(2);
    _exit(check() ? 0 : 1);
  }
  int status = 0;
  if (waitpid(child, &status, 0) != child) return false;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

}  // namespace bounce::test_support
