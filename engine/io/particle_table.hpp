#pragma once
// A particle file read into memory, before it is interpreted as particles: named columns
// of doubles, one row per particle. Readers (vtu.hpp, csv.hpp) fill it; particle_input.hpp
// turns it into positions, velocities and masses.
#include <cstddef>
#include <string>
#include <vector>

namespace pbf {

struct Column {
  std::string name;
  int components = 1;
  std::vector<double> values;  // count * components, interleaved (x0 y0 z0 x1 y1 z1 ...)
};

struct ParticleTable {
  std::string path;  // the file it came from, for error messages
  std::size_t count = 0;  // the rows here: the file's, or in a distributed run this rank's share
  std::vector<Column> columns;
  std::size_t first_row = 0, total = 0;  // the index of the first of them in the file; the file's rows

  // The column called `name`, or null.
  const Column* find(const std::string& name) const {
    for (const auto& c : columns)
      if (c.name == name) return &c;
    return nullptr;
  }
};

}  // namespace pbf
