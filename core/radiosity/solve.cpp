#include "radiosity/solve.h"

#include <chrono>

#include "base/memory_room.h"
#include "radiosity/memory_estimate.h"

namespace bounce {

bool mesh_for_solve(const scene& s, const solver_settings& settings, solve_setup& out, std::string& error) {
  const auto start = std::chrono::steady_clock::now();
  // A scene too large for the memory left is refused before the mesher
  // allocates anything (memory_estimate.h: the estimate is the least a
  // solve of it takes). Past the element limit the mesher says so itself.
  const solve_memory need = estimate_solve_memory(s, settings);
  const memory_room room = available_memory();
  if (need.elements <= double(max_patch_elements) && need.bytes > room.bytes) {
    error = "solving needs at least " + format_bytes(need.bytes) + " (" + describe(need) + "), more than the " +
            format_bytes(room.bytes) + " available (" + room.bound + "); use a larger --max-edge";
    return false;
  }
  auto mesh = std::make_shared<patch_mesh>();
  refinement_pass a_priori;
  mesher_params mesher = mesher_params_for(settings, s);
  mesher.a_priori_report = &a_priori;
  if (!make_patch_mesh(s, mesher, *mesh, error)) return false;
  out.mesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.mesh = std::move(mesh);
  out.a_priori = a_priori;
  return true;
}

std::unique_ptr<radiosity_solver> make_solver_for(const scene& s, const patch_mesh& mesh,
                                                  const solver_settings& settings) {
  return make_radiosity_solver(s, mesh, radiosity_params_for(settings));
}

bool start_solve(const scene& s, const solver_settings& settings, solve_setup& out, std::string& error) {
  solve_setup setup;
  if (!mesh_for_solve(s, settings, setup, error)) return false;
  setup.solver = make_solver_for(s, *setup.mesh, settings);
  out = std::move(setup);
  return true;
}

}  // namespace bounce
