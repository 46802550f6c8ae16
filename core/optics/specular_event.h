// What a specular surface does to light arriving on it: the split between
// mirror reflection and refraction, with Fresnel's equations where the
// material asks for them and total internal reflection. Shared by every
// pass that follows light through mirrors and glass (the ray tracer, the
// caustic photons, the radiosity solver's specular paths) so that they
// agree.
#pragma once

#include <algorithm>
#include <optional>

#include "scene/scene.h"
#include "optics/optics.h"

namespace bounce {

struct specular_event {
  rgb kr{0.0}, kt{0.0};  // after Fresnel and total internal reflection
  std::optional<vec3> refracted;
};

// Light along `d` meets material `m` where the shading normal facing it
// is `n` (dot(d, n) < 0); `front` is whether it arrives on the side the
// surface's normal points to, the outside (air).
inline specular_event specular_split(const material& m, const vec3& d, const vec3& n, bool front) {
  specular_event out;
  out.kr = m.kr;
  out.kt = m.kt;
  if (out.kt.r > 0.0 || out.kt.g > 0.0 || out.kt.b > 0.0) {
    const double n1 = front ? 1.0 : m.ior, n2 = front ? m.ior : 1.0;
    out.refracted = refract(d, n, n1, n2);
    if (m.fresnel) {
      const double f = fresnel_dielectric(std::min(1.0, -glm::dot(d, n)), n1, n2);
      out.kr += f * out.kt;
      out.kt *= 1.0 - f;
    }
    if (!out.refracted) {  // total internal reflection: all of it reflects
      out.kr += out.kt;
      out.kt = rgb(0.0);
    }
  }
  return out;
}

}  // namespace bounce
