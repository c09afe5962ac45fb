#pragma once
// The floating-point type of particle data, chosen at configure time (-DPBF_REAL=double|float).
namespace pbf {
using real = PBF_REAL;
}  // namespace pbf
