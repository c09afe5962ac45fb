#pragma once
// The stages of a time step, in the order of Macklin & Mueller's Algorithm 1, after the one
// point where particles may appear and disappear.
namespace pbf {

enum class Stage {
  exchange,         // particles added (emitters) and removed (outflow), before any other work
  external_forces,  // accelerations into velocities (gravity)
  predict,          // predicted positions from velocities (the integrator)
  neighbors,        // the engine rebuilds the grid and lists (no fix joins it)
  forces,           // interparticle forces that need neighbours (none for PBF)
  constraints,      // repeated `iterations` times: solver corrections, then boundaries
  velocity_update,  // velocities from corrected positions
  velocity_post,    // vorticity confinement, XSPH viscosity
  end_of_step,      // dumps, scripted callbacks (then thermo)
};
inline constexpr int kStageCount = 9;

inline const char* stage_name(Stage stage) {
  static const char* names[kStageCount] = {"exchange",        "external_forces", "predict",
                                           "neighbors",       "forces",
                                           "constraints",     "velocity_update", "velocity_post", "end_of_step"};
  return names[static_cast<int>(stage)];
}

}  // namespace pbf
