#include "radiosity/solution.h"

#include "base/check.h"
#include "radiosity/transfer/buried_vertices.h"

namespace bounce {

rgb ambient_radiosity(const patch_mesh& mesh, std::span<const rgb> remaining) {
  BOUNCE_CHECK_EQ(remaining.size(), mesh.element_count());
  rgb reflectance(0.0), unshot(0.0);
  double area = 0.0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    reflectance += element_mean(mesh, mesh.vertex_rho, e) * mesh.element_areas[e];
    unshot += remaining[e] * mesh.element_areas[e];
    area += mesh.element_areas[e];
  }
  if (!(area > 0.0)) return rgb(0.0);
  // Interreflection factor 1 + rho + rho^2 + ... of the mean reflectance.
  const rgb mean_rho = reflectance / area;
  // Light still to come is never negative: where the iterate overshoots
  // on the whole (the hierarchical residual is signed), the term is zero
  // rather than taking light away (it made early stills negative).
  return glm::max(unshot / area / (rgb(1.0) - mean_rho), rgb(0.0));
}

rgb mean_indirect_irradiance(const patch_mesh& mesh, const radiosity_snapshot& solution) {
  BOUNCE_CHECK_EQ(solution.radiosity.size(), mesh.vertex_count());
  rgb sum(0.0);
  double area = 0.0;
  for (std::size_t e = 0; e < mesh.element_count(); ++e) {
    rgb irradiance(0.0);
    for (int k = 0; k < 3; ++k) {
      const std::size_t v = std::size_t(mesh.elements[e][k]);
      const rgb indirect = solution.radiosity[v] - mesh.vertex_emission[v] - solution.direct[v];
      for (int c = 0; c < 3; ++c)
        if (mesh.vertex_rho[v][c] > 0.0) irradiance[c] += indirect[c] / mesh.vertex_rho[v][c] / 3.0;
    }
    sum += irradiance * mesh.element_areas[e];
    area += mesh.element_areas[e];
  }
  return area > 0.0 ? sum / area : rgb(0.0);
}

std::shared_ptr<const radiosity_snapshot> make_snapshot(const patch_mesh& mesh, std::span<const rgb> radiosity,
                                                        std::span<const rgb> direct, std::span<const rgb> caustic,
                                                        std::span<const rgb> remaining, const solver_stats& stats,
                                                        const std::vector<bool>& buried) {
  BOUNCE_CHECK_EQ(radiosity.size(), mesh.vertex_count());
  BOUNCE_CHECK_EQ(direct.size(), mesh.vertex_count());
  BOUNCE_CHECK(caustic.empty() || caustic.size() == mesh.vertex_count());
  BOUNCE_CHECK_EQ(remaining.size(), mesh.element_count());
  auto snap = std::make_shared<radiosity_snapshot>();
  snap->version = stats.steps + stats.refinements;
  snap->stats = stats;
  snap->ambient = ambient_radiosity(mesh, remaining);
  snap->radiosity.assign(radiosity.begin(), radiosity.end());
  snap->direct.assign(direct.begin(), direct.end());
  snap->caustic.assign(caustic.begin(), caustic.end());
  if (buried.size() == mesh.vertex_count()) {
    if (snap->caustic.empty())
      fill_buried_vertices(mesh, buried, {snap->radiosity, snap->direct});
    else
      fill_buried_vertices(mesh, buried, {snap->radiosity, snap->direct, snap->caustic});
  }
  std::vector<rgb> sum(mesh.vertex_count(), rgb(0.0));
  std::vector<int> count(mesh.vertex_count(), 0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      sum[std::size_t(mesh.elements[e][k])] += remaining[e];
      ++count[std::size_t(mesh.elements[e][k])];
    }
  snap->remaining.resize(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    snap->remaining[v] = count[v] ? sum[v] / double(count[v]) : rgb(0.0);
  return snap;
}

}  // namespace bounce
