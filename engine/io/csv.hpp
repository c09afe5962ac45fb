#pragma once
// Particles as CSV: a header line naming the columns, then one row per particle.
//
//     # a comment
//     x, y, z, vx, vy, vz, mass
//     0.1, 0.1, 0.2, 0, 0, 0, 0.008
//
// Fields are separated by commas, with optional spaces or tabs around them; blank lines and
// lines starting with '#' are skipped; quoting is not supported (numbers need none). In a
// distributed run each rank reads the header and its share of the rows (text_lines.hpp).
#include <string>

#include "engine/io/particle_table.hpp"

namespace pbf {

// Each header name becomes a 1-component Column. Errors name FILE:LINE (a row with the
// wrong number of fields, a field that is not a number, a duplicate or empty column name)
// or FILE (empty file, no data rows).
ParticleTable read_csv(const std::string& path);

}  // namespace pbf
