#pragma once
// Each style file defines one register_<style>() function; builtin_styles.cpp calls them all.
#include <memory>

#include "engine/registry/style_registry.hpp"

namespace pbf {

// Limits several styles share (SI units): beyond them a value is a slip of the unit rather
// than a fluid the engine can step.
inline constexpr double kMostAcceleration = 1e4;  // m/s^2, about 1000 g
inline constexpr double kMostSoundSpeed = 1e4;    // m/s, faster than sound in steel

// The factory of a compute style whose constructor takes (id, params).
template <class T>
auto make_compute() {
  return [](const std::string& id, const Params& p) { return std::make_unique<T>(id, p); };
}

void register_gravity(StyleRegistry&);
void register_spring(StyleRegistry&);
void register_pbf(StyleRegistry&);
void register_box(StyleRegistry&);
void register_solid(StyleRegistry&);
void register_vorticity(StyleRegistry&);
void register_xsph(StyleRegistry&);
void register_damping(StyleRegistry&);
void register_outflow(StyleRegistry&);
void register_emitter(StyleRegistry&);
void register_dump_text(StyleRegistry&);
void register_dump_vtk(StyleRegistry&);
void register_dump_image(StyleRegistry&);
void register_view(StyleRegistry&);
void register_dump_surface(StyleRegistry&);
void register_dump_movie(StyleRegistry&);
void register_restart(StyleRegistry&);
void register_wcsph(StyleRegistry&);
void register_dfsph(StyleRegistry&);
void register_sph_viscosity(StyleRegistry&);
void register_leapfrog(StyleRegistry&);
void register_cfl(StyleRegistry&);
void register_sample(StyleRegistry&);

void register_compute_density(StyleRegistry&);
void register_compute_density_error(StyleRegistry&);
void register_compute_iterations(StyleRegistry&);
void register_compute_kinetic_energy(StyleRegistry&);
void register_compute_potential_energy(StyleRegistry&);
void register_compute_speed(StyleRegistry&);
void register_compute_count(StyleRegistry&);
void register_compute_flow(StyleRegistry&);
void register_compute_extent(StyleRegistry&);
void register_compute_front(StyleRegistry&);
void register_compute_load(StyleRegistry&);
void register_compute_body(StyleRegistry&);
void register_compute_spring(StyleRegistry&);
void register_compute_probe(StyleRegistry&);
void register_compute_gauge(StyleRegistry&);

}  // namespace pbf
