// `bounce info`: load and validate a scene, print its counts (text or JSON).
#pragma once

#include <string>

namespace CLI {
class App;
}  // namespace CLI

namespace bounce {

struct info_options {
  std::string scene;      // SCENE; empty: the embedded Cornell box
  bool as_json = false;   // --json
  double max_edge = 0.0;  // tessellation size for curved surfaces; 0: the scene's default
};

void add_info_options(CLI::App& command, info_options& options);
int run_info(const info_options& options);

}  // namespace bounce
