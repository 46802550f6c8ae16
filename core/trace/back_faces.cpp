#include "trace/back_faces.h"

#include <cmath>
#include <cstdio>

#include "scene/camera_math.h"

namespace bounce {

double back_face_fraction(const scene& s, const camera& view, const ray_scene& rays, int grid) {
  camera c = view;
  c.width = c.height = grid;
  int hits = 0, backs = 0;
  for (int y = 0; y < grid; ++y)
    for (int x = 0; x < grid; ++x) {
      const vec3 d = camera_ray_direction(c, x + 0.5, y + 0.5);
      const auto hit = rays.intersect(c.eye, d);
      if (!hit) continue;
      ++hits;
      const bool back = glm::dot(d, hit->face_normal) > 0.0;
      backs += back && !s.materials[std::size_t(hit->material)].two_sided;
    }
  return hits > 0 ? double(backs) / hits : 0.0;
}

std::string back_face_warning(double fraction) {
  if (!(fraction > back_face_warning_fraction)) return {};
  char text[256];
  std::snprintf(text, sizeof text,
                "the camera sees mostly back faces (%.0f%% of what it hits): they receive no light and show black; "
                "turn the faces over or give their material \"two_sided\": true",
                100.0 * fraction);
  return text;
}

}  // namespace bounce
