#include "render/shader_files.h"

#include "base/check.h"

namespace bounce::gl {

shader_source shader_file(const std::string& name) {
  for (const embedded_file& f : shader_files())
    if (f.path == name) return {"shaders/" + name, std::string(f.contents)};
  check_failed(("unknown shader " + name).c_str(), __FILE__, __LINE__);  // the names are Bounce's own
}

}  // namespace bounce::gl
