// The one explicit list of built-in styles (no static initialisers a linker could drop).
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

void register_builtin_styles(StyleRegistry& r) {
  register_gravity(r);
  register_pbf(r);
  register_box(r);
  register_solid(r);
  register_spring(r);
  register_vorticity(r);
  register_xsph(r);
  register_wcsph(r);
  register_dfsph(r);
  register_sph_viscosity(r);
  register_leapfrog(r);
  register_cfl(r);
  register_damping(r);
  register_outflow(r);
  register_emitter(r);
  register_dump_text(r);
  register_dump_vtk(r);
  register_dump_image(r);
  register_dump_surface(r);
  register_dump_movie(r);
  register_restart(r);
  register_sample(r);
  register_view(r);
  register_compute_density(r);
  register_compute_density_error(r);
  register_compute_iterations(r);
  register_compute_kinetic_energy(r);
  register_compute_potential_energy(r);
  register_compute_speed(r);
  register_compute_count(r);
  register_compute_flow(r);
  register_compute_extent(r);
  register_compute_front(r);
  register_compute_load(r);
  register_compute_body(r);
  register_compute_spring(r);
  register_compute_probe(r);
  register_compute_gauge(r);
}

}  // namespace pbf
