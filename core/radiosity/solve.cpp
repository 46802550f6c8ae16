#include "radiosity/solve.h"

#include <chrono>

namespace bounce {

bool mesh_for_solve(const scene& s, const solver_settings& settings, solve_setup& out, std::string& error) {
  const auto start = std::chrono::steady_clock::now();
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
