#include "trace/photon_tracing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <optional>
#include <type_traits>
#include <variant>
#include <vector>

#include "base/directions.h"
#include "base/parallel.h"
#include "base/random_stream.h"
#include "optics/optics.h"
#include "optics/specular_event.h"
#include "scene/framing.h"
#include "scene/lights.h"
#include "scene/texture.h"

namespace bounce {
namespace {

using std::numbers::pi;

// What a hit does to a photon, on the side it arrived from: the material
// logic of the Whitted tracer's describe() (ray_tracer.cpp), which the
// caustics must agree with: two-sided partners, Fresnel and total internal
// reflection.
struct photon_hit {
  int surface = -1;
  vec3 n{0.0}, n_face{0.0};  // shading and geometric normals facing the photon
  rgb rho{0.0};              // diffuse reflectance with the texture, zero on back faces
  rgb kr{0.0}, kt{0.0};      // after Fresnel and total internal reflection
  std::optional<vec3> refracted;
};

photon_hit describe(const scene& s, const ray_hit& hit, const vec3& d) {
  photon_hit out;
  out.surface = hit.surface;
  vec3 normal = hit.normal, face = hit.face_normal;
  const material& m = s.materials[std::size_t(hit.material)];
  // A two-sided surface and its back lie on each other, and either may be
  // the hit: the one that faces the photon is the side it lands on.
  if (const surface& surf = s.surfaces[std::size_t(hit.surface)];
      glm::dot(d, face) >= 0.0 && m.two_sided && (surf.back_side >= 0 || surf.back_of >= 0)) {
    out.surface = surf.back_side >= 0 ? surf.back_side : surf.back_of;
    normal = -normal;
    face = -face;
  }
  const bool front = glm::dot(d, face) < 0.0;
  out.n_face = front ? face : -face;
  out.n = front ? normal : -normal;
  if (front) {
    out.rho = m.rho;
    if (m.texture >= 0) out.rho *= texture_value(s.textures[std::size_t(m.texture)], hit.uv);
  }
  // Outside is air; the front side is where the normal points.
  const specular_event event = specular_split(m, d, out.n, front);
  out.kr = event.kr;
  out.kt = event.kt;
  out.refracted = event.refracted;
  return out;
}

// Photons leave from one of these; the budget is shared in proportion to
// their power.
struct source {
  int light = -1;  // index into scene::lights, or -1 for all the area emitters together
  long first = 0;  // index of its first photon
  long count = 0;
  rgb power{0.0};  // punctual light: a photon's mean power
};

// One block of photons' share of the result, merged in block order so that
// the sums do not depend on the threads.
struct block_result {
  std::vector<photon> photons;
  photon_stats stats;
};

void add(photon_stats& to, const photon_stats& from) {
  to.emitted += from.emitted;
  to.stored += from.stored;
  to.emitted_power += from.emitted_power;
  to.stored_power += from.stored_power;
  to.direct_power += from.direct_power;
  to.absorbed_power += from.absorbed_power;
  to.escaped_power += from.escaped_power;
  to.truncated_power += from.truncated_power;
  to.passed_on_power += from.passed_on_power;
  to.reweighted_power += from.reweighted_power;
}

bool emits(const scene& s, const surface& surf) {
  auto lit = [&](int material) { return any_positive(s.materials[std::size_t(material)].ke); };
  return std::visit(
      [&](const auto& g) {
        if constexpr (std::is_same_v<std::decay_t<decltype(g)>, polygon_mesh>)
          return std::any_of(g.faces.begin(), g.faces.end(), [&](const polygon_face& f) { return lit(f.material); });
        else
          return lit(g.material);
      },
      surf.geometry);
}

class photon_tracer {
 public:
  photon_tracer(const scene& s, const ray_scene& rays, const photon_params& p, const vec3& centre, double radius)
      : s_(s), rays_(rays), p_(p), offset_(rays.surface_offset()), centre_(centre), radius_(radius) {}

  // Follows photon `index` of `src` and records where it ends.
  void trace(const source& src, long index, block_result& out) const {
    random_stream rng(p_.seed, std::uint64_t(index));
    vec3 origin, d;
    rgb power;
    if (src.light >= 0) {
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const light_photon start = sample_light_photon(s_.lights[std::size_t(src.light)], centre_, radius_, u1, u2);
      origin = start.origin;
      d = start.direction;
      power = src.power * start.weight;
    } else {
      // Stratified over the photons in u1, which sample_emitter carries
      // over to the emitters and the points on them.
      const double u1 = (double(index - src.first) + rng.uniform()) / double(src.count);
      const emitter_sample e = rays_.sample_emitter(u1, rng.uniform());
      origin = e.point + offset_ * e.normal;
      d = cosine_direction(e.normal, rng.uniform(), rng.uniform());
      power = pi * e.radiance / e.pdf_area / double(src.count);
    }
    photon_stats& st = out.stats;
    ++st.emitted;
    st.emitted_power += power;

    for (int specular = 0;; ++specular) {
      const auto hit = rays_.intersect(origin, d);
      if (!hit) {
        st.escaped_power += power;
        return;
      }
      const photon_hit ph = describe(s_, *hit, d);
      const bool diffuse = any_positive(ph.rho);
      const bool store = diffuse && specular > 0;  // L S+ D
      if (store) {
        out.photons.push_back({hit->point, -d, power, ph.n, ph.surface});
        ++st.stored;
        st.stored_power += power;
      }
      // Russian roulette on the specular weights (mean over channels): the
      // surviving photon keeps its power (for grey weights), so stored
      // photons all carry about the emitted photons' power.
      double p_mirror = channel_mean(ph.kr), p_transmit = ph.refracted ? channel_mean(ph.kt) : 0.0;
      const double sum = p_mirror + p_transmit;
      const bool normalise =
          sum > 1.0 + 1e-12;  // not for valid materials (rho + kr + kt <= 1); Fresnel's split rounds off
      if (normalise) {
        p_mirror /= sum;
        p_transmit /= sum;
      }
      const double pick = rng.uniform();
      const bool mirror = pick < p_mirror, transmit = !mirror && pick < p_mirror + p_transmit;
      if (!mirror && !transmit) {  // absorbed, or reflected diffusely: the caustic map stops here
        if (!store) (diffuse ? st.direct_power : st.absorbed_power) += power;
        return;
      }
      if (store) st.passed_on_power += power;
      if (specular >= p_.max_bounces) {
        st.truncated_power += power;
        return;
      }
      // Grey weights keep the power exactly (w / mean(w) rounds off otherwise).
      const rgb w = mirror ? ph.kr : ph.kt;
      const bool grey = w.r == w.g && w.g == w.b && !normalise;
      const rgb next = grey ? power : power * w / (mirror ? p_mirror : p_transmit);
      st.reweighted_power += next - power;
      power = next;
      if (mirror) {
        d = reflect(d, ph.n);
        origin = hit->point + offset_ * ph.n_face;
      } else {
        d = *ph.refracted;
        origin = hit->point - offset_ * ph.n_face;
      }
    }
  }

 private:
  const scene& s_;
  const ray_scene& rays_;
  photon_params p_;
  double offset_;
  vec3 centre_;    // of the ball about the scene that a sun's photons start beside
  double radius_;  // its radius
};

}  // namespace

caustic_result caustic_photons(const scene& s, const ray_scene& rays, const photon_params& params,
                               photon_progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  photon_stats stats;
  for (std::size_t i = 0; i < s.surfaces.size(); ++i)
    if (emits(s, s.surfaces[i]) && !rays.is_sampled_emitter(int(i))) ++stats.skipped_emitters;

  // The sources and their power. The area emitters' power, pi * ke * area
  // summed, is measured through the sampler (ray_scene keeps the
  // triangles): it only shares out the budget; each photon's own power
  // comes from the point it leaves.
  std::vector<source> sources;
  std::vector<double> shares;
  if (rays.emitter_area() > 0.0) {
    constexpr int n = 4096;
    rgb sum(0.0);
    for (int i = 0; i < n; ++i) sum += rays.sample_emitter((i + 0.5) / n, 0.5).radiance;
    const double power = pi * channel_mean(sum / double(n)) * rays.emitter_area();
    if (power > 0.0) {
      sources.push_back({-1, 0, 0, rgb(0.0)});
      shares.push_back(power);
    }
  }
  const bounds3 bounds = scene_bounds(s);
  const vec3 centre = 0.5 * (bounds.min + bounds.max);
  const double radius = std::max(0.5 * glm::length(bounds.max - bounds.min), 1e-12);
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const double power = channel_mean(emitted_power(s.lights[i], radius));
    if (power <= 0.0) continue;
    sources.push_back({int(i), 0, 0, rgb(0.0)});
    shares.push_back(power);
  }
  if (params.photon_count <= 0) {  // no budget: an empty map
    sources.clear();
    shares.clear();
  }
  double total_share = 0.0;
  for (double x : shares) total_share += x;
  // Rounded running sums: the counts add up to photon_count exactly (plus
  // one for each source too weak to get a photon of its own).
  const double budget = double(std::max(0L, params.photon_count));
  long total = 0;
  double share_so_far = 0.0;
  for (std::size_t k = 0; k < sources.size(); ++k) {
    source& src = sources[k];
    const long before = std::lround(budget * share_so_far / total_share);
    share_so_far += shares[k];
    src.first = total;
    src.count = std::max(1L, std::lround(budget * share_so_far / total_share) - before);
    if (src.light >= 0) src.power = emitted_power(s.lights[std::size_t(src.light)], radius) / double(src.count);
    total += src.count;
  }

  photon_progress local_progress;
  photon_progress& prog = progress ? *progress : local_progress;
  prog.photons_total = total;
  constexpr long block = 1024;
  const std::size_t blocks = std::size_t((total + block - 1) / block);
  std::vector<block_result> results(blocks);
  const photon_tracer tracer(s, rays, params, centre, radius);
  for_each_block(params.parallel, blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t b = begin; b < end && !prog.cancel.load(std::memory_order_relaxed); ++b) {
      const long first = long(b) * block, last = std::min(total, first + block);
      std::size_t k = 0;
      for (long i = first; i < last; ++i) {
        while (i >= sources[k].first + sources[k].count) ++k;
        tracer.trace(sources[k], i, results[b]);
      }
      prog.photons_done += last - first;
    }
  });

  std::size_t stored = 0;
  for (const block_result& r : results) stored += r.photons.size();
  std::vector<photon> photons;
  photons.reserve(stored);
  for (block_result& r : results) {
    photons.insert(photons.end(), r.photons.begin(), r.photons.end());
    add(stats, r.stats);
  }
  stats.cancelled = prog.cancel;
  caustic_result out{photon_map(std::move(photons)), stats};
  out.stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

rgb photon_power_imbalance(const photon_stats& st) {
  return st.emitted_power + st.reweighted_power + st.passed_on_power -
         (st.stored_power + st.direct_power + st.absorbed_power + st.escaped_power + st.truncated_power);
}

double caustic_power_fraction(const photon_stats& st) {
  const double emitted = channel_mean(st.emitted_power);
  return emitted > 0.0 ? channel_mean(st.stored_power) / emitted : 0.0;
}

}  // namespace bounce
