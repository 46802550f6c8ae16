#include "optics/optics.h"

#include <algorithm>
#include <cmath>

namespace bounce {

vec3 reflect(const vec3& d, const vec3& n) {
  return d - 2.0 * glm::dot(d, n) * n;
}

std::optional<vec3> refract(const vec3& d, const vec3& n, double n1, double n2) {
  const double eta = n1 / n2;
  const double cos_i = -glm::dot(d, n);
  const double sin2_t = eta * eta * std::max(0.0, 1.0 - cos_i * cos_i);
  if (sin2_t > 1.0) return std::nullopt;  // beyond the critical angle
  const double cos_t = std::sqrt(1.0 - sin2_t);
  return glm::normalize(eta * d + (eta * cos_i - cos_t) * n);
}

double fresnel_dielectric(double cos_incident, double n1, double n2) {
  const double cos_i = std::clamp(std::abs(cos_incident), 0.0, 1.0);
  const double sin_t = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
  if (sin_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(std::max(0.0, 1.0 - sin_t * sin_t));
  const double parallel = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  const double perpendicular = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  return 0.5 * (parallel * parallel + perpendicular * perpendicular);
}

}  // namespace bounce
