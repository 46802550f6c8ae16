// What the solver options of the command line (and the panel) stand for in
// the core's parameters.
#include "adaptive.h"
#include "cli.h"
#include "patch_mesh.h"
#include "radiosity.h"
#include "scene_info.h"

namespace bounce {

radiosity_params to_radiosity_params(const solver_options& o) {
  radiosity_params p;
  p.form_factors.method = o.method == "hemicube" ? form_factor_method::hemicube : form_factor_method::raycast;
  p.form_factors.shadow_rays = o.shadow_rays;
  p.form_factors.hemicube_resolution = o.hemicube_resolution;
  p.form_factors.adaptive_rays = !o.full_rays;
  p.adaptive.enabled = o.adaptive;
  p.adaptive.tolerance = o.tolerance;
  p.adaptive.min_edge = o.min_edge;
  return p;
}

mesher_params to_mesher_params(const solver_options& o, const scene& s) {
  mesher_params p;
  if (o.adaptive) {
    // Adaptive meshing starts coarser and lets elements shoot, so that the
    // shooters refine with the receivers: measured on the Cornell box, 4x
    // patches over a refined mesh kept its error at 3.4-7% (README).
    p.max_edge = o.max_edge > 0.0 ? o.max_edge : adaptive_start_edge(s);
    p.patch_edge = o.patch_edge < 0.0 ? 0.0 : o.patch_edge;
    p.a_priori_min_edge = o.min_edge > 0.0 ? o.min_edge : default_min_edge(p.max_edge);
    return p;
  }
  p.max_edge = o.max_edge > 0.0 ? o.max_edge : default_max_edge(s);
  // Patches of about 16 elements shoot by default: measured on the Cornell
  // box, 10x faster to 1e-4 unshot than element shooting, 1.2% mean
  // deviation from its solution (README).
  p.patch_edge = o.patch_edge < 0.0 ? 4.0 * p.max_edge : o.patch_edge;
  return p;
}

stop_criterion to_stop_criterion(const solver_options& o) {
  stop_criterion c;
  c.unshot_fraction = o.until;
  c.max_shots = static_cast<std::uint64_t>(o.max_shots);
  c.seconds = o.seconds;
  return c;
}

}  // namespace bounce
