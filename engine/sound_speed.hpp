#pragma once
// The weakly compressible solver's sound speed c0. By default 10 sqrt(2 g H), H the fluid's
// height when it is first measured (the z extent of the particles plus one spacing): flow
// speeds stay below about sqrt(2 g H), so the Mach number stays under 0.1 and the density
// varies by about 1% (Monaghan 1994). One rule for every style that needs c0.
namespace pbf {

class Simulation;

double default_sound_speed(const Simulation& sim, double gravity);

}  // namespace pbf
