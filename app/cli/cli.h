// The `bounce` command line: the options of the whole program, its
// subcommands (each owns its options: *_command.h) and the run without one.
// One parser for every command.
#pragma once

namespace bounce {

// Parses the command line, runs the command chosen and returns the exit
// code (exit_code.h).
int run_cli(int argc, char** argv);

}  // namespace bounce
