#include "trace/ray_tracer.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <span>
#include <stdexcept>
#include <vector>

#include "base/directions.h"
#include "base/parallel.h"
#include "base/random_stream.h"
#include "image/image_metrics.h"
#include "image/tonemap.h"
#include "optics/optics.h"
#include "optics/specular_event.h"
#include "scene/camera_math.h"
#include "scene/framing.h"
#include "scene/lights.h"
#include "scene/sky.h"
#include "scene/texture.h"
#include "trace/irradiance_cache.h"
#include "trace/progressive_photons.h"

namespace bounce {
namespace {

using std::numbers::pi;

// n stratified points in [0,1)^2 (Latin hypercube: each row and each
// column of an n x n grid holds one point), for any n.
void stratified_points(int n, random_stream& rng, std::vector<vec2>& out) {
  out.resize(n);
  for (int i = 0; i < n; ++i) out[i] = {(i + rng.uniform()) / n, (i + rng.uniform()) / n};
  for (int i = n - 1; i > 0; --i) std::swap(out[i].y, out[std::size_t(rng.next_bits() % std::uint64_t(i + 1))].y);
}

// Weight of a sample drawn with density `chosen` when `other` could have
// drawn it too (both per solid angle).
double power_heuristic(double chosen, double other) {
  return chosen * chosen / (chosen * chosen + other * other);
}

struct counters {
  std::uint64_t primary = 0, shadow = 0, secondary = 0, gather = 0, misses = 0;
  std::vector<caustic_hit>* hits = nullptr;  // ppm: where caustic shading points go instead of being estimated
  int pixel = -1;                            // ... and the pixel they are for
};

// A diffuse point that a pixel centre's specular tree reaches: where the
// irradiance cache may want a record.
struct cache_point {
  vec3 position{0.0}, n{0.0}, n_face{0.0};
  double footprint = 0.0;  // a pixel's width at the point's distance along the eye path
  int pixel = 0, index = 0;
};

// What a hit offers for shading, on the side the ray arrived from.
struct surface_point {
  const material* mat = nullptr;
  ray_hit hit;
  bool front = true;        // the ray arrived on the surface's own side
  vec3 n{0.0};              // shading normal facing the ray
  vec3 n_face{0.0};         // geometric normal facing the ray
  rgb rho{0.0};             // diffuse reflectance with the texture, zero on back faces
  rgb texture_detail{1.0};  // texture / its mean: what the radiosity pass averaged away
  rgb ke{0.0};              // emitted radiance as seen here: the emission texture's detail included
  rgb kr{0.0}, kt{0.0};     // mirror and transmission weights after Fresnel and TIR
  std::optional<vec3> refracted;
};

class tracer {
 public:
  tracer(const scene& s, const camera& view, const ray_scene& rays, const radiosity_field* field, const trace_params& p)
      : s_(s), view_(view), camera_(view), rays_(rays), field_(field), p_(p), offset_(rays.surface_offset()) {
    for (const texture& tex : s.textures) texture_means_.push_back(texture_mean(tex));
    const bounds3 b = scene_bounds(s);
    scene_diagonal_ = std::max(glm::length(b.max - b.min), 1e-12);
    pixel_angle_ = 2.0 * std::tan(view.fov_y_degrees * pi / 360.0) / std::max(1, view.height);
    final_gather_ = p.method == integrator::twopass || p.method == integrator::ppm;
  }

  void set_caustics(const photon_map* map, double radius, int k) {
    caustics_ = map && !map->empty() ? map : nullptr;
    caustic_radius_ = radius;
    caustic_k_ = k;
  }
  void set_cache(const irradiance_cache* cache) { cache_ = cache; }
  double scene_diagonal() const { return scene_diagonal_; }

  // The diffuse points that pixel (x, y)'s centre reaches through its
  // specular tree, as whitted() follows it.
  void shading_points(int x, int y, std::vector<cache_point>& out) const {
    const vec3 d = camera_.direction(x + 0.5, y + 0.5);
    shading_points(view_.eye, d, 0, rgb(1.0), 0.0, y * view_.width + x, out);
  }

  // A final gather at a diffuse point: the irradiance record, with R
  // clamped between what a pixel can resolve and a tenth of the scene.
  irradiance_record gather(const vec3& point, const vec3& n, const vec3& n_face, double footprint, std::uint64_t seed,
                           counters& c) const {
    irradiance_record r;
    const vec3 origin = point + offset_ * n_face;
    gather_irradiance(
        point, n, p_.gather_rays, seed,
        [&](const vec3& dir, std::uint64_t ray_seed) {
          if (glm::dot(dir, n_face) <= 0.0)  // below the true surface (interpolated normals)
            return gather_sample{rgb(0.0), std::numeric_limits<double>::infinity()};
          random_stream rng(p_.seed, ray_seed, 3);
          return gather_ray(origin, dir, rng, c);
        },
        r);
    const double a = std::max(p_.cache_accuracy, 1e-6);
    const double lo = 2.0 * footprint / a, hi = std::max(lo, 0.1 * scene_diagonal_);
    r.radius = std::clamp(r.radius, lo, hi);
    return r;
  }

  rgb pixel(int x, int y, int samples, std::uint64_t pass, counters& c) const {
    random_stream rng(p_.seed, std::uint64_t(y) * std::uint64_t(view_.width) + std::uint64_t(x), pass);
    std::vector<vec2> offsets;
    if (samples <= 1)
      offsets.assign(1, vec2(0.5));
    else
      stratified_points(samples, rng, offsets);
    rgb sum(0.0);
    const std::size_t first_hit = c.hits ? c.hits->size() : 0;
    c.pixel = y * view_.width + x;
    // The samples of one pixel are coherent: their camera rays go in
    // packets of 8 (docs/performance.md, "Ray core").
    constexpr std::size_t packet = 8;
    std::array<vec3, packet> eyes, directions;
    eyes.fill(view_.eye);
    std::array<std::optional<ray_hit>, packet> hits;
    for (std::size_t begin = 0; begin < offsets.size(); begin += packet) {
      const std::size_t count = std::min(packet, offsets.size() - begin);
      for (std::size_t i = 0; i < count; ++i)
        directions[i] = camera_.direction(x + offsets[begin + i].x, y + offsets[begin + i].y);
      rays_.intersect_packets(std::span(eyes.data(), count), std::span(directions.data(), count),
                              std::span(hits.data(), count));
      for (std::size_t i = 0; i < count; ++i) {
        ++c.primary;
        sum += p_.method == integrator::path ? path(view_.eye, directions[i], hits[i], rng, c)
                                             : whitted(directions[i], hits[i], 0, rgb(1.0), rng, c);
      }
    }
    if (c.hits)
      for (std::size_t i = first_hit; i < c.hits->size(); ++i) (*c.hits)[i].weight /= double(offsets.size());
    return sum / double(offsets.size());
  }

 private:
  surface_point describe(const ray_hit& hit, const vec3& d) const {
    surface_point sp;
    sp.hit = hit;
    // A two-sided surface and its back lie on each other, and either may be
    // the hit: the one that faces the ray is the side seen.
    if (const surface& surf = s_.surfaces[std::size_t(hit.surface)];
        glm::dot(d, hit.face_normal) >= 0.0 && s_.materials[std::size_t(hit.material)].two_sided &&
        (surf.back_side >= 0 || surf.back_of >= 0)) {
      sp.hit.surface = surf.back_side >= 0 ? surf.back_side : surf.back_of;
      sp.hit.normal = -hit.normal;
      sp.hit.face_normal = -hit.face_normal;
    }
    sp.mat = &s_.materials[hit.material];
    sp.front = glm::dot(d, sp.hit.face_normal) < 0.0;
    sp.n_face = sp.front ? sp.hit.face_normal : -sp.hit.face_normal;
    sp.n = sp.front ? sp.hit.normal : -sp.hit.normal;
    if (sp.front) {
      sp.rho = sp.mat->rho;
      if (sp.mat->texture >= 0) {
        const texture& t = s_.textures[sp.mat->texture];
        const rgb value = texture_value(t, hit.uv), mean = texture_means_[sp.mat->texture];
        sp.rho *= value;
        for (int c = 0; c < 3; ++c) sp.texture_detail[c] = mean[c] > 0.0 ? value[c] / mean[c] : 0.0;
      }
      sp.ke = sp.mat->ke;
      if (sp.mat->emission_texture >= 0 && any_positive(sp.ke)) {
        const int t = sp.mat->emission_texture;
        const rgb value = texture_value(s_.textures[std::size_t(t)], hit.uv), mean = texture_means_[std::size_t(t)];
        for (int c = 0; c < 3; ++c) sp.ke[c] *= mean[c] > 0.0 ? value[c] / mean[c] : 0.0;
      }
    }
    // Outside is air; the front side is where the normal points.
    const specular_event split = specular_split(*sp.mat, d, sp.n, sp.front);
    sp.kr = split.kr;
    sp.kt = split.kt;
    sp.refracted = split.refracted;
    return sp;
  }

  // Normalised Phong lobe, (n + 2) / (2 pi) cos^n of the angle between the
  // light's mirror direction and the viewer.
  rgb phong(const surface_point& sp, const vec3& to_light, const vec3& to_viewer) const {
    if (sp.mat->shininess <= 0.0 || !any_positive(sp.mat->specular)) return rgb(0.0);
    const double c = glm::dot(reflect(-to_light, sp.n), to_viewer);
    if (c <= 0.0) return rgb(0.0);
    return sp.mat->specular * (sp.mat->shininess + 2.0) / (2.0 * pi) * std::pow(c, sp.mat->shininess);
  }

  // Direct irradiance at a front-facing point from the point lights and
  // `samples` stratified points on the area emitters, and the Phong
  // highlight it makes.
  //
  // With `mis_lobe_probability` > 0 (the path tracer), each emitter sample
  // is weighted by the power heuristic against the chance that cosine
  // sampling of the diffuse lobe, picked with that probability, finds the
  // same direction (Veach 1997): near contact edges the 1/d^2 of light
  // sampling otherwise leaves fireflies.
  void direct_light(const surface_point& sp, const vec3& to_viewer, int samples, random_stream& rng, counters& c,
                    rgb& irradiance, rgb& highlight, double mis_lobe_probability = 0.0) const {
    const vec3 origin = sp.hit.point + offset_ * sp.n_face;
    for (const punctual_light& light : s_.lights) {
      const light_arrival a = light_at(light, sp.hit.point, 4.0 * scene_diagonal_);
      const vec3 l = a.to_light;
      const double cos_x = glm::dot(sp.n, l);
      if (cos_x <= 0.0 || glm::dot(sp.n_face, l) <= 0.0 || !any_positive(a.irradiance)) continue;
      ++c.shadow;
      if (rays_.occluded(origin, a.shadow_end)) continue;
      const rgb e = a.irradiance * cos_x;
      irradiance += e;
      highlight += phong(sp, l, to_viewer) * e;
    }
    if (s_.sky.on() && mis_lobe_probability == 0.0 && samples > 0) {
      // Whitted's sky: `samples` stratified, cosine-weighted shadow rays
      // (the path tracer finds the sky with its bounces instead).
      const double far = 4.0 * scene_diagonal_;
      const std::uint64_t seed = rng.next_bits();
      rgb sum(0.0);
      for (int k = 0; k < samples; ++k) {
        const vec3 l = stratified_cosine_direction(sp.n, k, samples, seed);
        if (glm::dot(sp.n_face, l) <= 0.0) continue;
        ++c.shadow;
        if (!rays_.occluded(origin, origin + far * l)) sum += sky_radiance(s_.sky, l);
      }
      irradiance += sum * (pi / samples);
    }
    if (samples <= 0 || rays_.emitter_area() <= 0.0) return;
    std::vector<vec2> points;
    stratified_points(samples, rng, points);
    for (const vec2& u : points) {
      const emitter_sample es = rays_.sample_emitter(u.x, u.y);
      const vec3 to = es.point - sp.hit.point;
      const double d2 = glm::dot(to, to);
      if (d2 <= 0.0) continue;
      const vec3 l = to / std::sqrt(d2);
      const double cos_x = glm::dot(sp.n, l), cos_e = -glm::dot(es.normal, l);
      if (cos_x <= 0.0 || cos_e <= 0.0 || glm::dot(sp.n_face, l) <= 0.0) continue;
      ++c.shadow;
      if (rays_.occluded(origin, es.point + offset_ * es.normal)) continue;
      double weight = 1.0;
      if (mis_lobe_probability > 0.0)
        weight = power_heuristic(es.pdf_area * d2 / cos_e, mis_lobe_probability * cos_x / pi);
      const rgb e = es.radiance * (weight * cos_x * cos_e / d2 / es.pdf_area / samples);
      irradiance += e;
      highlight += phong(sp, l, to_viewer) * e;
    }
  }

  rgb whitted(const vec3& origin, const vec3& d, int depth, const rgb& weight, random_stream& rng, counters& c) const {
    return whitted(d, rays_.intersect(origin, d), depth, weight, rng, c);
  }

  // The same, from the ray's hit found beforehand (a camera ray's, in a packet).
  rgb whitted(const vec3& d, const std::optional<ray_hit>& hit, int depth, const rgb& weight, random_stream& rng,
              counters& c) const {
    if (!hit) return escaped_radiance(s_, d);
    const surface_point sp = describe(*hit, d);
    rgb radiance = sp.ke;

    if (sp.front && final_gather_) {
      // Two-pass with a final gather: direct light by shadow rays, caustics
      // from the photons, and the rest of the diffuse light from the cache.
      const bool diffuse = any_positive(sp.rho);
      const bool shiny = sp.mat->shininess > 0.0 && any_positive(sp.mat->specular);
      if (diffuse || shiny) {
        rgb irradiance(0.0), highlight(0.0);
        direct_light(sp, -d, p_.light_samples, rng, c, irradiance, highlight);
        radiance += sp.rho / pi * irradiance + highlight;
      }
      if (diffuse) {
        if (c.hits)
          c.hits->push_back({hit->point, sp.n, weight * sp.rho / pi, c.pixel});
        else if (caustics_)
          radiance += sp.rho / pi * caustics_->irradiance_estimate(hit->point, sp.n, caustic_radius_, caustic_k_);
        radiance += sp.rho / pi * indirect_irradiance(sp, rng, c);
      }
    } else if (sp.front) {
      const bool diffuse = any_positive(sp.rho);
      const bool shiny = sp.mat->shininess > 0.0 && any_positive(sp.mat->specular);
      const bool solution = field_ && p_.diffuse != diffuse_source::ambient;
      const bool traced_direct = !solution || p_.diffuse == diffuse_source::traced_direct;
      if ((diffuse && traced_direct) || shiny) {
        rgb irradiance(0.0), highlight(0.0);
        direct_light(sp, -d, p_.light_samples, rng, c, irradiance, highlight);
        if (traced_direct) radiance += sp.rho / pi * irradiance;
        radiance += highlight;
      }
      if (diffuse) {
        if (solution) {
          const diffuse_radiosity b = field_->at(sp.hit.surface, hit->point, sp.n_face);
          const rgb reflected = p_.diffuse == diffuse_source::radiosity ? b.reflected : b.indirect;
          radiance += reflected * sp.texture_detail / pi;
        } else {
          radiance += sp.rho * p_.ambient_irradiance / pi;
        }
      }
    }

    if (depth + 1 >= p_.max_depth) return radiance;
    if (channel_max(weight * sp.kr) > p_.min_weight) {
      ++c.secondary;
      radiance +=
          sp.kr * whitted(hit->point + offset_ * sp.n_face, reflect(d, sp.n), depth + 1, weight * sp.kr, rng, c);
    }
    if (sp.refracted && channel_max(weight * sp.kt) > p_.min_weight) {
      ++c.secondary;
      radiance += sp.kt * whitted(hit->point - offset_ * sp.n_face, *sp.refracted, depth + 1, weight * sp.kt, rng, c);
    }
    return radiance;
  }

  // What a final gather ray brings back to the diffuse point it left: the
  // solution's reflected radiance (B - E) / pi where it lands on a diffuse
  // surface (caustic light there, L S+ D D, is the solver's own specular
  // transfer: the photon map is not asked, which would count it twice),
  // going on through mirrors and glass by one branch picked in proportion
  // to its weight. Emitters that shadow rays sample, and the sky, are
  // direct light and count nothing here; seen through mirrors and glass
  // they are caustics, the photon map's. The background (no sky) counts:
  // shadow rays do not find it.
  gather_sample gather_ray(vec3 origin, vec3 d, random_stream& rng, counters& c) const {
    gather_sample out{rgb(0.0), std::numeric_limits<double>::infinity()};
    rgb throughput(1.0);
    for (int depth = 0;; ++depth) {
      ++c.gather;
      const auto hit = rays_.intersect(origin, d);
      if (!hit) {
        if (!s_.sky.on()) out.radiance += throughput * s_.background;
        return out;
      }
      if (depth == 0) out.distance = hit->t;
      const surface_point sp = describe(*hit, d);
      if (any_positive(sp.ke) && !rays_.is_sampled_emitter(sp.hit.surface)) out.radiance += throughput * sp.ke;
      if (any_positive(sp.rho)) {
        const diffuse_radiosity b = field_->at(sp.hit.surface, hit->point, sp.n_face);
        if (depth > 0 && caustics_ && sp.front) {
          // Seen through a mirror or a lens, a small patch of surface
          // fills much of the hemisphere, so the detail of the caustic on
          // it matters: the photons' estimate replaces the solution's
          // smooth share of the lights' light through mirrors and glass.
          // (Through glass, the ceiling above a glass ball sees the
          // focused spot under it.)
          out.radiance += throughput *
                          ((b.reflected - b.caustic) * sp.texture_detail / pi +
                           sp.rho / pi * caustics_->irradiance_estimate(hit->point, sp.n, caustic_radius_, caustic_k_));
        } else {
          out.radiance += throughput * b.reflected * sp.texture_detail / pi;
        }
      }
      if (depth + 1 >= p_.max_depth) return out;
      const double p_mirror = channel_mean(sp.kr), p_transmit = sp.refracted ? channel_mean(sp.kt) : 0.0;
      const double pick = rng.uniform() * std::max(1.0, p_mirror + p_transmit);
      if (pick < p_mirror) {
        throughput *= sp.kr / p_mirror;
        d = reflect(d, sp.n);
        origin = hit->point + offset_ * sp.n_face;
      } else if (pick < p_mirror + p_transmit) {
        throughput *= sp.kt / p_transmit;
        d = *sp.refracted;
        origin = hit->point - offset_ * sp.n_face;
      } else {
        return out;
      }
      if (p_mirror + p_transmit > 1.0) throughput *= p_mirror + p_transmit;
    }
  }

  // The indirect irradiance at a diffuse point: interpolated from the
  // cache's records (Ward's test, then twice its reach for sub-pixel
  // samples between the pixel centres' records), or gathered on the spot.
  rgb indirect_irradiance(const surface_point& sp, random_stream& rng, counters& c) const {
    if (cache_) {
      for (double reach : {1.0, irradiance_cache::max_reach})
        if (const std::optional<rgb> e = cache_->lookup(sp.hit.point, sp.n, reach)) return *e;
      ++c.misses;
    }
    return gather(sp.hit.point, sp.n, sp.n_face, 0.0, rng.next_bits(), c).irradiance;
  }

  void shading_points(const vec3& origin, const vec3& d, int depth, const rgb& weight, double length, int pixel,
                      std::vector<cache_point>& out) const {
    const auto hit = rays_.intersect(origin, d);
    if (!hit) return;
    const surface_point sp = describe(*hit, d);
    const double travelled = length + hit->t;
    if (sp.front && any_positive(sp.rho))
      out.push_back({hit->point, sp.n, sp.n_face, travelled * pixel_angle_, pixel, int(out.size())});
    if (depth + 1 >= p_.max_depth) return;
    if (channel_max(weight * sp.kr) > p_.min_weight)
      shading_points(hit->point + offset_ * sp.n_face, reflect(d, sp.n), depth + 1, weight * sp.kr, travelled, pixel,
                     out);
    if (sp.refracted && channel_max(weight * sp.kt) > p_.min_weight)
      shading_points(hit->point - offset_ * sp.n_face, *sp.refracted, depth + 1, weight * sp.kt, travelled, pixel, out);
  }

  // Unbiased path tracing: next-event estimation to the point lights and
  // the area emitters at diffuse vertices (combined with the diffuse
  // bounce by multiple importance sampling), one lobe chosen per bounce in
  // proportion to its weight, Russian roulette after a few bounces.
  // `first` is the camera ray's hit, found beforehand in a packet.
  rgb path(vec3 origin, vec3 d, const std::optional<ray_hit>& first, random_stream& rng, counters& c) const {
    rgb radiance(0.0), throughput(1.0);
    double diffuse_pdf = 0.0;  // solid-angle density of the last bounce if it was diffuse; 0 after specular ones
    for (int bounce = 0;; ++bounce) {
      const auto hit = bounce == 0 ? first : rays_.intersect(origin, d);
      if (!hit) {
        // The sky is found by the bounces' own cosine sampling, which is
        // importance sampling for a diffuse surface under a smooth sky.
        radiance += throughput * escaped_radiance(s_, d);
        break;
      }
      const surface_point sp = describe(*hit, d);
      if (sp.front && any_positive(sp.mat->ke)) {
        // Emitters that next-event estimation samples share the diffuse
        // bounce's share with it (MIS); the rest count in full.
        double weight = 1.0;
        if (diffuse_pdf > 0.0 && rays_.is_sampled_emitter(sp.hit.surface)) {
          const double cos_e = -glm::dot(d, hit->face_normal);
          weight = power_heuristic(diffuse_pdf, hit->t * hit->t / (cos_e * rays_.emitter_area()));
        }
        // Seen from the camera or in a mirror, an emission texture's detail;
        // as light found by a diffuse bounce, its mean, as next-event
        // estimation samples it.
        radiance += throughput * (diffuse_pdf > 0.0 ? sp.mat->ke : sp.ke) * weight;
      }
      if (bounce + 1 >= p_.max_path) break;

      const double p_diffuse = channel_mean(sp.rho), p_mirror = channel_mean(sp.kr),
                   p_transmit = sp.refracted ? channel_mean(sp.kt) : 0.0;
      const double total = p_diffuse + p_mirror + p_transmit;
      if (total <= 0.0) break;
      if (p_diffuse > 0.0) {
        rgb irradiance(0.0), unused(0.0);
        direct_light(sp, -d, 1, rng, c, irradiance, unused, p_diffuse / total);
        radiance += throughput * sp.rho / pi * irradiance;
      }
      const double pick = rng.uniform() * total;
      if (pick < p_diffuse) {
        d = cosine_direction(sp.n, rng.uniform(), rng.uniform());
        if (glm::dot(d, sp.n_face) <= 0.0) break;  // below the true surface (interpolated normals)
        throughput *= sp.rho * (total / p_diffuse);
        origin = hit->point + offset_ * sp.n_face;
        diffuse_pdf = p_diffuse / total * glm::dot(d, sp.n) / pi;
      } else if (pick < p_diffuse + p_mirror) {
        d = reflect(d, sp.n);
        throughput *= sp.kr * (total / p_mirror);
        origin = hit->point + offset_ * sp.n_face;
        diffuse_pdf = 0.0;
      } else {
        d = *sp.refracted;
        throughput *= sp.kt * (total / p_transmit);
        origin = hit->point - offset_ * sp.n_face;
        diffuse_pdf = 0.0;
      }
      ++c.secondary;
      if (bounce + 1 >= p_.roulette_depth) {
        const double survive = std::min(0.95, channel_max(throughput));
        if (survive <= 0.0 || rng.uniform() >= survive) break;
        throughput /= survive;
      }
    }
    return radiance;
  }

  const scene& s_;
  const camera& view_;
  const camera_rays camera_;  // the view's basis, once for all its rays
  const ray_scene& rays_;
  const radiosity_field* field_;
  trace_params p_;
  double offset_;
  double scene_diagonal_ = 1.0;     // shadow rays to the sky end this far beyond any point
  std::vector<rgb> texture_means_;  // what the radiosity pass multiplied rho by
  double pixel_angle_ = 0.0;        // a pixel's width over the distance
  bool final_gather_ = false;       // twopass, ppm
  const photon_map* caustics_ = nullptr;
  double caustic_radius_ = 0.0;
  int caustic_k_ = 0;
  const irradiance_cache* cache_ = nullptr;
};

}  // namespace

long default_caustic_photons(const scene& s, integrator method) {
  const bool specular = std::any_of(s.materials.begin(), s.materials.end(),
                                    [](const material& m) { return any_positive(m.kr) || any_positive(m.kt); });
  if (!specular) return 0;
  return method == integrator::ppm ? 200000 : 500000;
}

double default_caustic_radius(const scene& s, integrator method) {
  const bounds3 b = scene_bounds(s);
  const double diagonal = std::max(glm::length(b.max - b.min), 1e-12);
  return diagonal * (method == integrator::ppm ? 0.01 : 0.02);
}

namespace {

// The cache's records, made before the pixels so that the picture does not
// depend on the threads: the pixel centres' shading points are visited
// coarse to fine (every 16th pixel, then every 8th, ... every one), and at
// each level those no record covers yet get one, gathered in parallel and
// added in pixel order.
void make_cache(const tracer& t, const camera& view, const trace_params& params, trace_progress& prog,
                irradiance_cache& cache, counters& total) {
  const int w = view.width, h = view.height;
  std::vector<std::vector<cache_point>> points(std::size_t(w) * h);
  for_each_block(params.parallel, std::size_t(h), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t y = begin; y < end && !prog.cancel.load(std::memory_order_relaxed); ++y)
      for (int x = 0; x < w; ++x) t.shading_points(x, int(y), points[y * std::size_t(w) + std::size_t(x)]);
  });
  std::size_t all = 0;
  for (const auto& p : points) all += p.size();
  prog.cache_points_total = long(all);
  std::mutex mutex;
  for (int stride = 16; stride >= 1 && !prog.cancel; stride /= 2) {
    std::vector<const cache_point*> level;
    for (int y = 0; y < h; y += stride)
      for (int x = 0; x < w; x += stride) {
        if (stride < 16 && x % (2 * stride) == 0 && y % (2 * stride) == 0) continue;  // a coarser level's
        for (const cache_point& p : points[std::size_t(y) * w + x]) level.push_back(&p);
      }
    std::vector<char> uncovered(level.size(), 0);
    for_each_block(params.parallel, level.size(), 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) uncovered[i] = !cache.lookup(level[i]->position, level[i]->n);
    });
    std::vector<std::size_t> wanted;
    for (std::size_t i = 0; i < level.size(); ++i)
      if (uncovered[i]) wanted.push_back(i);
    std::vector<irradiance_record> made(wanted.size());
    for_each_block(params.parallel, wanted.size(), 4, [&](std::size_t begin, std::size_t end) {
      counters c;
      for (std::size_t k = begin; k < end && !prog.cancel.load(std::memory_order_relaxed); ++k) {
        const cache_point& p = *level[wanted[k]];
        const std::uint64_t seed = (std::uint64_t(p.pixel) << 8 | std::uint64_t(p.index)) * 0x9E3779B97F4A7C15ull;
        made[k] = t.gather(p.position, p.n, p.n_face, p.footprint, seed ^ params.seed, c);
      }
      const std::lock_guard lock(mutex);
      total.gather += c.gather;
    });
    for (const irradiance_record& r : made)
      if (r.radius > 0.0) cache.add(r);
    prog.cache_points_done += long(level.size());
  }
}

struct caustic_pass {
  caustic_result photons;
  double seconds = 0.0;
};

caustic_pass shoot(const scene& s, const ray_scene& rays, const trace_params& params, long count, int pass,
                   trace_progress& prog) {
  photon_params pp;
  pp.photon_count = count;
  pp.seed = params.seed * 0x2545F4914F6CDD1Dull + std::uint64_t(pass);
  pp.parallel = params.parallel;
  prog.photons.photons_done = 0;
  prog.photons.cancel = prog.cancel.load();
  caustic_pass out{caustic_photons(s, rays, pp, &prog.photons)};
  out.seconds = out.photons.stats.seconds;
  return out;
}

}  // namespace

image trace_image(const scene& s, const camera& view, const ray_scene& rays, const radiosity_field* field,
                  const trace_params& params, trace_progress* progress, trace_stats* stats) {
  const auto start = std::chrono::steady_clock::now();
  const bool final_gather = params.method == integrator::twopass || params.method == integrator::ppm;
  if (final_gather && !field)
    throw std::invalid_argument("trace_image: the twopass and ppm integrators need a radiosity solution");
  tracer t(s, view, rays, field, params);
  image img;
  img.width = view.width;
  img.height = view.height;
  img.pixels.assign(std::size_t(img.width) * img.height * 3, 0.0f);
  trace_progress local_progress;
  trace_progress& prog = progress ? *progress : local_progress;
  std::mutex stats_mutex;
  counters total;
  trace_stats st;

  // Caustic photons: twopass's map, or ppm's first pass.
  const long photon_count =
      final_gather ? (params.photons >= 0 ? params.photons : default_caustic_photons(s, params.method)) : 0;
  const double caustic_radius =
      params.caustic_radius > 0.0 ? params.caustic_radius : default_caustic_radius(s, params.method);
  caustic_pass first;
  if (photon_count > 0 && !prog.cancel) {
    prog.stage = trace_stage::photons;
    prog.passes_total = params.method == integrator::ppm ? std::max(1, params.passes) : 1;
    first = shoot(s, rays, params, photon_count, 1, prog);
    st.photons_emitted += first.photons.stats.emitted;
    st.photons_stored += first.photons.stats.stored;
    st.photon_seconds += first.seconds;
    if (params.method == integrator::twopass) t.set_caustics(&first.photons.map, caustic_radius, params.caustic_k);
  }
  irradiance_cache cache(std::max(params.cache_accuracy, 1e-6), 0.01 * t.scene_diagonal());
  if (final_gather && params.cache_accuracy > 0.0 && !prog.cancel) {
    prog.stage = trace_stage::cache;
    const auto cache_start = std::chrono::steady_clock::now();
    make_cache(t, view, params, prog, cache, total);
    st.cache_records = cache.size();
    st.cache_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - cache_start).count();
    t.set_cache(&cache);
  }

  // One pass over a list of pixels (all of them, or those to refine), in
  // rows of pixels handed out to TBB's threads. ppm keeps each chunk's
  // caustic shading points in chunk order.
  const bool progressive = params.method == integrator::ppm && photon_count > 0;
  std::vector<std::vector<caustic_hit>> chunk_hits;
  auto trace_pixels = [&](std::size_t count, auto&& pixel_at, int samples, std::uint64_t pass) {
    constexpr std::size_t chunk = 64;
    if (progressive) chunk_hits.assign((count + chunk - 1) / chunk, {});
    for_each_block(params.parallel, (count + chunk - 1) / chunk, 1, [&](std::size_t begin, std::size_t end) {
      counters c;
      for (std::size_t block = begin; block < end && !prog.cancel.load(std::memory_order_relaxed); ++block) {
        c.hits = progressive ? &chunk_hits[block] : nullptr;
        const std::size_t last = std::min(count, (block + 1) * chunk);
        for (std::size_t k = block * chunk; k < last; ++k) {
          const int i = pixel_at(k);
          const rgb value = t.pixel(i % img.width, i / img.width, samples, pass, c);
          for (int ch = 0; ch < 3; ++ch) img.pixels[3 * std::size_t(i) + ch] = float(value[ch]);
        }
        prog.pixels_done += long(last - block * chunk);
      }
      const std::lock_guard lock(stats_mutex);
      total.primary += c.primary;
      total.shadow += c.shadow;
      total.secondary += c.secondary;
      total.gather += c.gather;
      total.misses += c.misses;
    });
  };

  const std::size_t pixel_count = std::size_t(img.width) * img.height;
  prog.stage = trace_stage::pixels;
  prog.pixels_total = long(pixel_count);
  trace_pixels(
      pixel_count, [](std::size_t k) { return int(k); }, params.spp, 0);
  std::uint64_t refined = 0;
  // (ppm does not refine: its caustic points belong to the first samples.)
  if (params.adaptive_spp > params.spp && !prog.cancel && !progressive) {
    const std::vector<bool> marked = contrast_edges(img, params.adaptive_contrast);
    std::vector<int> edges;
    for (std::size_t i = 0; i < marked.size(); ++i)
      if (marked[i]) edges.push_back(int(i));
    refined = edges.size();
    prog.pixels_total += long(edges.size());
    trace_pixels(
        edges.size(), [&](std::size_t k) { return edges[k]; }, params.adaptive_spp, 1);
  }

  if (progressive && !prog.cancel) {
    // Progressive photon passes over the caustic points found above: each
    // pass's box estimate at its radius, averaged over the passes.
    std::vector<caustic_hit> hits;
    for (auto& v : chunk_hits) hits.insert(hits.end(), v.begin(), v.end());
    chunk_hits.clear();
    const auto passes_start = std::chrono::steady_clock::now();
    prog.stage = trace_stage::passes;
    const caustic_hit_grid grid(hits, caustic_radius);
    std::vector<rgb> irradiance(hits.size(), rgb(0.0));
    // The picture with the caustic of `passes` passes: their mean.
    auto with_caustic = [&](int passes) {
      std::vector<rgb> caustic(pixel_count, rgb(0.0));
      for (std::size_t h = 0; h < hits.size(); ++h)
        caustic[std::size_t(hits[h].pixel)] += hits[h].weight * irradiance[h];
      image out = img;
      for (std::size_t i = 0; i < pixel_count; ++i)
        for (int ch = 0; ch < 3; ++ch) out.pixels[3 * i + ch] += float(caustic[i][ch] / passes);
      return out;
    };
    grid.add_pass(first.photons.map.photons(), caustic_radius, irradiance);
    int passes = 1;
    prog.passes_done = 1;
    if (prog.pass_done) prog.pass_done(with_caustic(1), 1);
    double radius = caustic_radius;
    for (int pass = 2; pass <= std::max(1, params.passes) && !prog.cancel; ++pass) {
      const caustic_pass next = shoot(s, rays, params, photon_count, pass, prog);
      if (next.photons.stats.cancelled) break;
      st.photons_emitted += next.photons.stats.emitted;
      st.photons_stored += next.photons.stats.stored;
      radius = ppm_radius(caustic_radius, pass, params.ppm_alpha);
      grid.add_pass(next.photons.map.photons(), radius, irradiance);
      passes = pass;
      prog.passes_done = pass;
      if (prog.pass_done && pass < params.passes) prog.pass_done(with_caustic(pass), pass);
    }
    img = with_caustic(passes);
    st.passes = passes;
    st.final_radius = radius;
    st.photon_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - passes_start).count();
  }
  if (stats) {
    *stats = st;
    stats->primary_rays = total.primary;
    stats->shadow_rays = total.shadow;
    stats->secondary_rays = total.secondary;
    stats->gather_rays = total.gather;
    stats->cache_misses = total.misses;
    stats->refined_pixels = refined;
    stats->cancelled = prog.cancel;
    stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return img;
}

}  // namespace bounce
