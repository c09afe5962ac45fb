#pragma once
// The particle-file fuzz targets (.vtu and .csv): read the file, find the particles among
// its columns, and add them to a simulation, as `pbf.read_particles` does. Reading and
// interpreting either give consistent columns and particles, or refuse the file with a
// pbf::Error naming it; adding the particles either works or is a pbf::Error (outside the
// domain, or the simulation's checks of scale and resolution).
#include <utility>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/io/load_particles.hpp"
#include "engine/io/particle_input.hpp"
#include "fuzz_input.hpp"

namespace pbf::fuzz {

inline void load_particles(const InputFile& input, const std::uint8_t* data, std::size_t size) {
  const std::string& path = input.write(data, size);
  ParticleTable table;
  ParticleInput in;
  try {
    table = read_particle_file(path);
    for (const Column& c : table.columns)
      check(c.components >= 1 && c.values.size() == table.count * static_cast<std::size_t>(c.components),
            "a column's size does not match the particle count:", c.name);
    in = interpret_particles(table);
  } catch (const Error& e) {
    check_names(e, path);
    return;
  }
  check(in.x.size() == table.count && in.vz.size() == table.count, "positions or velocities are missing");
  try {
    Simulation sim;
    // [-1, 1]^3 and h = 0.05: the seeds' particles lie inside, at 2 to 5 per h (resolution.hpp
    // refuses fewer than 1 or more than 10); mutated ones often outside.
    Domain domain;
    for (int a = 0; a < 3; ++a) domain.lo[a] = -1;
    sim.set_domain(domain);
    sim.set_kernel_radius(0.05);
    sim.set_timestep(0.001);
    add_particles(sim, std::move(in), path);
    check(sim.particles().size() == table.count, "not every particle was added");
  } catch (const Error&) {  // refused, as it may be
  }
}

}  // namespace pbf::fuzz
