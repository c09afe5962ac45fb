#pragma once
// Adding particles from data a file supplied, with the one mass rule for files
// (engine/mass.hpp) when the file gives no masses. The original scene format and the
// .vtu/.csv particle files all end here.
#include <cstddef>
#include <string>
#include <vector>

namespace pbf {

class Simulation;

struct LoadedParticles {
  std::size_t count = 0;
  double mass = 0;            // the mass given to each particle (0: masses came from the file)
  std::vector<std::string> ignored;  // file columns not used
};

// Positions and velocities in file order; `mass` empty: the mass rule. Every position must
// lie inside the domain (the error names `source` and the particle's 0-based index).
LoadedParticles add_particles(Simulation& sim, const std::vector<double>& x, const std::vector<double>& y,
                              const std::vector<double>& z, const std::vector<double>& vx,
                              const std::vector<double>& vy, const std::vector<double>& vz,
                              const std::vector<double>& mass, const std::string& source);

// A .vtu (for example a dump/vtk frame, filtered in ParaView) or a .csv with a header.
LoadedParticles load_particle_file(Simulation& sim, const std::string& path);

}  // namespace pbf
