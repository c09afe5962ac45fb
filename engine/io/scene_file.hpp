#pragma once
// The original study's scene format: six header values (particle count N, time step,
// particle size taken as the kernel radius h, cubic domain side L, output interval, final
// time), whitespace-separated on one line or several, then N lines "x y z vx vy vz".
// Lines starting with '#' are comments. Every error names the file and line. In a distributed
// run each rank reads the header and its share of the particle lines (text_lines.hpp).
#include <cstdint>
#include <string>
#include <vector>

namespace pbf {

class Simulation;

struct SceneFile {
  std::string path;
  std::int64_t count = 0;
  double dt = 0, h = 0, L = 0, interval = 0, t_final = 0;
  // x y z vx vy vz per particle, in file order: this process's share of the lines (all of them
  // in one process), the first of which is particle first_row of the file.
  std::vector<double> particles;
  std::size_t first_row = 0;
};

SceneFile read_scene_file(const std::string& path);

// Domain [0, L]^3, kernel radius, time step, and the particles with the file mass rule.
// Returns the mass given to each particle.
double load_scene(Simulation& sim, const SceneFile& scene);

}  // namespace pbf
