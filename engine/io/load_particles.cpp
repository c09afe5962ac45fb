#include "engine/io/load_particles.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/io/particle_input.hpp"
#include "engine/sph/mass.hpp"
#include "engine/core/simulation.hpp"

namespace pbf {

LoadedParticles add_particles(Simulation& sim, const std::vector<double>& x, const std::vector<double>& y,
                              const std::vector<double>& z, const std::vector<double>& vx,
                              const std::vector<double>& vy, const std::vector<double>& vz,
                              const std::vector<double>& mass, const std::string& source) {
  if (sim.kernel_radius() <= 0)
    throw Error(fmt::format("{}: set the kernel radius (pbf.kernel_radius) before reading particles", source));
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
  LoadedParticles loaded{n, 0, {}};
  if (mass.empty()) {
    const MassEstimate m =
        mass_from_positions(rx.data(), ry.data(), rz.data(), n, sim.domain(), sim.kernels(), sim.rest_density());
    if (m.interior == 0)
      spdlog::warn("{}: no particle is at least h = {} from every face; mass from the nearest-neighbour spacing {:.4g}",
                   source, sim.kernel_radius(), m.spacing);
    loaded.mass = m.mass;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const real p[3] = {rx[i], ry[i], rz[i]}, v[3] = {real(vx[i]), real(vy[i]), real(vz[i])};
    sim.particles().add(p, v, real(mass.empty() ? loaded.mass : mass[i]));
  }
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
