#include "engine/io/load_particles.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/io/particle_input.hpp"
#include "engine/sph/mass.hpp"
#include "engine/sph/resolution.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

LoadedParticles add_particles(Simulation& sim, const std::vector<double>& x, const std::vector<double>& y,
                              const std::vector<double>& z, const std::vector<double>& vx,
                              const std::vector<double>& vy, const std::vector<double>& vz,
                              const std::vector<double>& mass, const std::string& source) {
  if (sim.kernel_radius() <= 0)
    throw Error(fmt::format("{}: set the kernel radius (pbf.kernel_radius) before reading particles", source));
  try {
    sim.check_scale();  // the domain and h a scene file has just set
  } catch (const Error& e) {
    throw Error(fmt::format("{}: {}", source, e.what()));
  }
  const std::size_t n = x.size();
  std::vector<real> rx(n), ry(n), rz(n);
  for (std::size_t i = 0; i < n; ++i) {
    rx[i] = real(x[i]);
    ry[i] = real(y[i]);
    rz[i] = real(z[i]);
    if (!sim.domain().contains(rx[i], ry[i], rz[i]))
      throw Error(fmt::format("{}: particle {} at ({}, {}, {}) is outside the domain", source, i, x[i], y[i], z[i]),
                  true);
  }
  check_memory_for(sim.particles(), static_cast<double>(n), source);
  // Before the mass rule, whose neighbour lists grow as (h/s)^3.
  const double spacing = sampled_spacing(rx.data(), ry.data(), rz.data(), n);
  check_kernel_radius(sim.kernel_radius(), spacing, source);
  // Masses from the file must describe a fluid near the rest density: a particle of mass m
  // at spacing s stands for a density of about m / s^3.
  for (std::size_t i = 0; i < mass.size() && spacing > 0; ++i) {
    const double ratio = mass[i] / (spacing * spacing * spacing) / sim.rest_density();
    if (!(ratio > 1e-3 && ratio < 1e3))
      throw Error(fmt::format("{}: particle {} has mass {} kg, {:.3g} times what a particle at the spacing {:.4g} m "
                              "of rest density {} kg/m^3 has: masses in another unit, or the wrong rest density?",
                              source, i, mass[i], ratio, spacing, sim.rest_density()),
                  true);
  }
  LoadedParticles loaded{n, 0, {}};
  if (mass.empty()) {
    const MassEstimate m =
        mass_from_positions(rx.data(), ry.data(), rz.data(), n, sim.domain(), sim.kernels(), sim.rest_density());
    if (m.interior == 0)
      spdlog::warn("{}: no particle is at least h = {} from every face; mass from the nearest-neighbour spacing {:.4g}",
                   source, sim.kernel_radius(), m.spacing);
    loaded.mass = m.mass;
  }
  // In a distributed run each rank keeps its share of the rows (the whole file is read, checked
  // and weighed alike on every rank).
  Particles& P = sim.particles();
  const Particles::Share share = P.share(n);
  const std::size_t first = P.size();
  for (std::size_t i = share.first; i < share.end; ++i) {
    const real p[3] = {rx[i], ry[i], rz[i]}, v[3] = {real(vx[i]), real(vy[i]), real(vz[i])};
    P.add(p, v, real(mass.empty() ? loaded.mass : mass[i]));
  }
  P.finish_source(first);
  sim.positions_changed();
  return loaded;
}

LoadedParticles load_particle_file(Simulation& sim, const std::string& path) {
  const ParticleInput in = interpret_particles(read_particle_file(path));
  LoadedParticles loaded = add_particles(sim, in.x, in.y, in.z, in.vx, in.vy, in.vz, in.mass, path);
  loaded.ignored = in.ignored;
  return loaded;
}

}  // namespace pbf
