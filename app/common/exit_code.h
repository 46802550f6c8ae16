// The exit codes of `bounce`, which every command returns and the tests
// check: 0 done, 1 an input that cannot be used (or not within --time), 2 a
// bad command line.
#pragma once

namespace bounce {

enum exit_code : int {
  exit_ok = 0,
  exit_input_error = 1,  // a scene or file that cannot be used
  exit_usage = 2,        // bad command line
};

}  // namespace bounce
