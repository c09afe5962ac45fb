// Fuzz target: the original study's scene format (engine/io/scene_file.cpp), read and then
// loaded into a simulation as `pbf.read_scene` does. The reader either gives what the
// header promised or refuses the file with a pbf::Error naming it (and the line); loading
// a scene it accepted either works or is a pbf::Error (the simulation's own checks of scale
// and resolution, which know no file).
#include <cmath>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/io/scene_file.hpp"
#include "fuzz_input.hpp"

using namespace pbf;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const fuzz::InputFile input("scene.txt");
  const std::string& path = input.write(data, size);
  SceneFile scene;
  try {
    scene = read_scene_file(path);
  } catch (const Error& e) {
    fuzz::check_names(e, path);
    return 0;
  }
  fuzz::check(scene.count > 0 && scene.particles.size() == 6 * static_cast<std::size_t>(scene.count),
              "the particle lines do not match the count N");
  try {
    Simulation sim;
    load_scene(sim, scene);
    fuzz::check(sim.particles().size() == static_cast<std::size_t>(scene.count), "not every particle was loaded");
  } catch (const Error&) {  // refused, as it may be
  }
  return 0;
}
