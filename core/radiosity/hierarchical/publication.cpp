#include "radiosity/hierarchical/publication.h"

#include "radiosity/hierarchical/final_gather.h"
#include "radiosity/hierarchical/solver.h"
#include "radiosity/hierarchical/specular_passes.h"

namespace bounce {

std::vector<rgb> element_to_vertex(const patch_mesh& mesh, const std::vector<rgb>& per_element) {
  std::vector<rgb> sum(mesh.vertex_count(), rgb(0.0));
  std::vector<double> area(mesh.vertex_count(), 0.0);
  for (std::size_t e = 0; e < mesh.element_count(); ++e)
    for (int k = 0; k < 3; ++k) {
      sum[std::size_t(mesh.elements[e][k])] += per_element[e] * mesh.element_areas[e];
      area[std::size_t(mesh.elements[e][k])] += mesh.element_areas[e];
    }
  for (std::size_t v = 0; v < sum.size(); ++v)
    if (area[v] > 0.0) sum[v] /= area[v];
  return sum;
}

bool solution_final(const hierarchical_solver& solver) {
  return refinement_done(solver) && specular_passes_done(solver);
}

vertex_light publish_vertex_light(hierarchical_solver& h) {
  const patch_mesh& mesh = h.mesh();
  const element_sources& src = h.sources;
  vertex_light out;
  const bool gathered = solution_final(h) && h.residual_fraction <= h.params.refine_below && final_gather(h);
  // Where the gather left a vertex out (with a view, one the view does not
  // see), the element solution stands, averaged to it by area.
  const std::vector<bool>& at = h.gathered_at;
  const bool everywhere = at.empty();
  if (gathered) {
    // Gathered at the vertices: the point lights included; their light by
    // way of mirrors and glass stays per element.
    out.radiosity.resize(mesh.vertex_count());
    out.direct = h.gathered.direct;
    const std::vector<rgb> specular =
        src.specular_lamp.empty() ? std::vector<rgb>() : element_to_vertex(mesh, src.specular_lamp);
    for (std::size_t v = 0; v < out.radiosity.size(); ++v)
      out.radiosity[v] = mesh.vertex_emission[v] + h.gathered.total[v] + (specular.empty() ? rgb(0.0) : specular[v]);
    if (!everywhere) {
      const std::vector<rgb> total = element_to_vertex(mesh, h.light.total);
      const std::vector<rgb> direct = element_to_vertex(mesh, h.light.direct);
      for (std::size_t v = 0; v < out.radiosity.size(); ++v)
        if (!at[v]) {
          out.radiosity[v] = total[v];
          out.direct[v] = direct[v];
        }
    }
  } else {
    out.radiosity = element_to_vertex(mesh, h.light.total);
    out.direct = element_to_vertex(mesh, h.light.direct);
  }
  // The lights' light through mirrors and glass enters B as a
  // right-hand-side term, and through the links through mirrors: B's
  // caustic part is that term plus what those links bring from the emitters.
  if (!src.specular_lamp_input.empty() || !h.hierarchy.mirror_links.empty() || !src.mirrored_lamp.empty()) {
    std::vector<rgb> caustic(mesh.element_count(), rgb(0.0));
    if (!src.specular_lamp_input.empty())
      for (std::size_t e = 0; e < caustic.size(); ++e)
        caustic[e] = src.specular_lamp_input[std::size_t(h.meshes.input_element[e])];
    // Per element, what the gather finds at the vertices: the links
    // through mirrors and the lights seen in mirrors.
    std::vector<rgb> mirrored(mesh.element_count(), rgb(0.0));
    for (std::size_t e = 0; e < mirrored.size() && e < h.light.mirrored.size(); ++e) mirrored[e] = h.light.mirrored[e];
    for (std::size_t e = 0; e < mirrored.size() && e < src.mirrored_lamp.size(); ++e)
      mirrored[e] += src.mirrored_lamp[e];
    std::vector<rgb> mirrored_per_vertex;
    if (!gathered)
      for (std::size_t e = 0; e < caustic.size(); ++e) caustic[e] += mirrored[e];
    else if (!everywhere)
      mirrored_per_vertex = element_to_vertex(mesh, mirrored);
    out.caustic = element_to_vertex(mesh, caustic);
    if (gathered)
      for (std::size_t v = 0; v < out.caustic.size(); ++v)
        out.caustic[v] += everywhere || at[v]           ? h.gathered.mirrored[v]
                          : mirrored_per_vertex.empty() ? rgb(0.0)
                                                        : mirrored_per_vertex[v];
  }
  return out;
}

}  // namespace bounce
