#include "engine/io/load_particles.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <utility>

#include "engine/core/error.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/particle_input.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/resolution.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

LoadedParticles add_particles(Simulation& sim, ParticleInput in, const std::string& source) {
  if (sim.kernel_radius() <= 0)
    throw Error(fmt::format("{}: set the kernel radius (pbf.kernel_radius) before reading particles", source));
  try {
    sim.check_scale();  // the domain and h a scene file has just set
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", source, e.what()));
  }
  Particles& P = sim.particles();
  const std::size_t n = in.x.size();
  std::vector<real> rx(n), ry(n), rz(n);
  for (std::size_t i = 0; i < n; ++i) {
    rx[i] = real(in.x[i]);
    ry[i] = real(in.y[i]);
    rz[i] = real(in.z[i]);
    if (!sim.domain().contains(rx[i], ry[i], rz[i]))
      throw Error(fmt::format("{}: particle {} at ({}, {}, {}) is outside the domain", source, in.first_row + i,
                              in.x[i], in.y[i], in.z[i]),
                  true);
  }
  check_memory_for(P, static_cast<double>(n), source);
  // Before the mass rule, whose neighbour lists grow as (h/s)^3.
  const double spacing = sampled_spacing_of_shares(rx.data(), ry.data(), rz.data(), n, P.distributed());
  check_kernel_radius(sim.kernel_radius(), spacing, source);
  // Masses from the file must describe a fluid near the rest density: a particle of mass m
  // at spacing s stands for a density of about m / s^3.
  for (std::size_t i = 0; in.has_mass && i < n && spacing > 0; ++i) {
    const double ratio = in.mass[i] / (spacing * spacing * spacing) / sim.rest_density();
    if (!(ratio > 1e-3 && ratio < 1e3))
      throw Error(fmt::format("{}: particle {} has mass {} kg, {:.3g} times what a particle at the spacing {:.4g} m "
                              "of rest density {} kg/m^3 has: masses in another unit, or the wrong rest density?",
                              source, in.first_row + i, in.mass[i], ratio, spacing, sim.rest_density()),
                  true);
  }
  const std::size_t first = P.size();
  const std::int64_t first_id = P.next_id();  // the same on every rank
  for (std::size_t i = 0; i < n; ++i) {
    const real p[3] = {rx[i], ry[i], rz[i]}, v[3] = {real(in.vx[i]), real(in.vy[i]), real(in.vz[i])};
    P.add(p, v, in.has_mass ? real(in.mass[i]) : real(0));
  }
  LoadedParticles loaded{P.finish_source(first), 0, std::move(in.ignored)};
  sim.positions_changed();
  const bool has_mass = in.has_mass;
  // The file's values are in the particles now: freed before the mass rule's neighbour lists.
  in = ParticleInput{};
  rx = ry = rz = std::vector<real>{};
  if (!has_mass) {  // the mass rule over the file's particles, wherever they now are
    const MassEstimate m = file_mass(sim, first_id, first_id + static_cast<std::int64_t>(loaded.count));
    if (m.interior == 0)
      spdlog::warn("{}: no particle is at least h = {} from every face; mass from the nearest-neighbour spacing {:.4g}",
                   source, sim.kernel_radius(), m.spacing);
    loaded.mass = m.mass;
    const std::int64_t* id = P.ids();
    real* mass = P.mass();
    for (std::size_t i = 0; i < P.size(); ++i)
      if (id[i] >= first_id) mass[i] = real(m.mass);
    sim.positions_changed();  // (the ghosts' copies hold the old masses)
  }
  return loaded;
}

LoadedParticles load_particle_file(Simulation& sim, const std::string& path) {
  ParticleInput in = interpret_particles(read_particle_file(path));  // the file's table freed here
  return add_particles(sim, std::move(in), path);
}

}  // namespace pbf
