#pragma once
// The stages of a time step, in the order of Macklin & Mueller's Algorithm 1, after the one
// point where particles may appear and disappear, with one stage more for solvers that keep
// the velocity field divergence-free (DFSPH): docs/design.md, "The step".
namespace pbf {

enum class Stage {
  exchange,         // particles added (emitters) and removed (outflow), before any other work
  external_forces,  // accelerations into velocities (gravity)
  predict,          // predicted positions from velocities (the integrator)
  neighbors,        // the engine rebuilds the grid and lists (no fix joins it)
  divergence,       // repeated: a velocity solve at the new positions (dfsph's divergence-free solve)
  forces,           // interparticle forces that need neighbours (none for PBF)
  constraints,      // repeated: solver corrections (pbf's positions, dfsph's velocities), then boundaries
  velocity_update,  // velocities from corrected positions
  velocity_post,    // vorticity confinement, XSPH viscosity
  end_of_step,      // dumps, scripted callbacks (then thermo)
};
inline constexpr int kStageCount = 10;

inline const char* stage_name(Stage stage) {
  static const char* names[kStageCount] = {"exchange",        "external_forces", "predict",
                                           "neighbors",       "divergence",      "forces",
                                           "constraints",     "velocity_update", "velocity_post", "end_of_step"};
  return names[static_cast<int>(stage)];
}

}  // namespace pbf
