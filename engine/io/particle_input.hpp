#pragma once
// Particle files as input to a scene: read any supported format, then find positions,
// velocities and masses among its columns.
#include <string>
#include <vector>

#include "engine/io/particle_table.hpp"

namespace pbf {

// By extension (case-insensitive): .vtu (vtu.hpp) or .csv (csv.hpp); anything else is an
// error listing the supported ones.
ParticleTable read_particle_file(const std::string& path);

// This process's share of a file's particles (all of them in one process; ParticleTable).
struct ParticleInput {
  std::vector<double> x, y, z, vx, vy, vz;
  bool has_mass = false;             // whether the file has a "mass" column
  std::vector<double> mass;
  std::size_t first_row = 0, total = 0;  // the first one's index in the file; the file's count
  std::vector<std::string> ignored;  // columns not used, in file order, for the caller to log
};

// Position from a 3-component "position" column or scalar columns x, y, z; velocity from a
// 3-component "velocity" or vx, vy, vz (zero if absent); mass from "mass" if present (each
// > 0 and finite). Errors name the file: no position (listing the columns found), a column
// of the wrong shape, half a vector (x and y but no z), a non-finite position or velocity or
// a bad mass (naming the particle index, 0-based, in file order), no particles.
ParticleInput interpret_particles(const ParticleTable& table);

}  // namespace pbf
