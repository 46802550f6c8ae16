#include "radiosity/memory_estimate.h"

#include <cstdio>

#include "base/memory_room.h"
#include "radiosity/hierarchical/link_table.h"
#include "radiosity/hierarchical/params.h"

namespace bounce {

solve_memory estimate_solve_memory(const scene& s, const solver_settings& settings) {
  solve_memory out;
  out.max_edge = mesher_params_for(settings, s).max_edge;
  out.elements = estimate_patch_elements(s, out.max_edge);
  out.bytes = solve_base_bytes + out.elements * solve_bytes_per_element;
  if (settings.method == solver_method::hierarchical)
    out.link_bytes = double(hierarchical_params{}.max_links) * double(sizeof(hierarchy_link));
  return out;
}

std::string describe(const solve_memory& need) {
  char text[160];
  if (need.elements >= 999'500)  // "1 million", not "999999.9"
    std::snprintf(text, sizeof text, "about %.3g million elements at max edge %.3g, ", need.elements / 1e6,
                  need.max_edge);
  else
    std::snprintf(text, sizeof text, "about %.0f elements at max edge %.3g, ", need.elements, need.max_edge);
  return text + format_bytes(solve_bytes_per_element) + " each";
}

}  // namespace bounce
