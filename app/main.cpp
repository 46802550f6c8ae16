#include "cli/cli.h"

int main(int argc, char** argv) {
  return bounce::run_cli(argc, argv);
}
