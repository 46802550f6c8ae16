#include "render/shader_files.h"

#include <cassert>

namespace bounce::gl {

shader_source shader_file(const std::string& name) {
  for (const embedded_file& f : shader_files())
    if (f.path == name) return {"shaders/" + name, std::string(f.contents)};
  assert(!"unknown shader");
  return {"shaders/" + name, ""};
}

}  // namespace bounce::gl
