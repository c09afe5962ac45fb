#pragma once
// Adding particles from data a file supplied, with the one mass rule for files
// (engine/mass.hpp) when the file gives no masses. The original scene format and the
// .vtu/.csv particle files all end here.
#include <cstddef>
#include <string>
#include <vector>

#include "engine/io/particle_input.hpp"

namespace pbf {

class Simulation;

struct LoadedParticles {
  std::size_t count = 0;
  double mass = 0;            // the mass given to each particle (0: masses came from the file)
  std::vector<std::string> ignored;  // file columns not used
};

// This process's share of a file's particles (all of them in one process), in file order;
// without masses, the mass rule over the whole file. Every position must lie inside the
// domain (the error names `source` and the particle's 0-based index in the file). Collective in
// a distributed run. `in` is freed once its particles are added, before the mass rule's
// neighbour lists are built.
LoadedParticles add_particles(Simulation& sim, ParticleInput in, const std::string& source);

// A .vtu (for example a dump/vtk frame, filtered in ParaView) or a .csv with a header.
LoadedParticles load_particle_file(Simulation& sim, const std::string& path);

}  // namespace pbf
