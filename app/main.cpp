#include <cstdio>
#include <new>

#include "cli/cli.h"
#include "common/exit_code.h"

int main(int argc, char** argv) {
  // Out of memory anywhere (a worker's is passed on to the thread that
  // waits for it) is an error with a reason, not an abort.
  try {
    return bounce::run_cli(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fputs(
        "error: out of memory: the scene needs more than this process may use (the machine's memory, or ulimit -v); "
        "try a coarser mesh (--max-edge) or a smaller picture\n",
        stderr);
    return bounce::exit_input_error;
  }
}
