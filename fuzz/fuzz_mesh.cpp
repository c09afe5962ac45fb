// Fuzz target: triangle meshes (engine/geometry/mesh_file.cpp), read through Assimp and then
// checked as the `solid` fix checks them. The first byte picks the extension hint: 'o' for
// "obj", 's' for "stl", anything else none (Assimp then asks every reader it has, as for a
// file of an extension it does not know); the rest is the file. A mesh is either read, with
// what the reader promises (triangles, indices in range, finite coordinates within 1e6 m, no
// repeated corner), or refused with a pbf::Error naming it; orient_surface may refuse any
// mesh with a pbf::Error naming it, and a mesh it takes has a finite volume and nothing left
// to turn (a second pass, which refuses any triangle it would turn, changes nothing).
#include <cmath>
#include <string>

#include "engine/core/error.hpp"
#include "engine/geometry/mesh_file.hpp"
#include "engine/geometry/mesh_surface.hpp"
#include "fuzz_input.hpp"

using namespace pbf;

// Assimp 5.2.5 leaks the mesh it was building when it refuses a file (its OBJ reader on a
// face index out of range, for one): not ours to fix, and no harm in a command that stops
// at the error. Leaks of allocations made inside libassimp are not findings; ours still are.
extern "C" const char* __lsan_default_suppressions() { return "leak:libassimp.so\n"; }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    spdlog::set_level(spdlog::level::off);
    return true;
  }();
  (void)quiet;
  if (size == 0) return 0;
  const std::string hint = data[0] == 'o' ? "obj" : data[0] == 's' ? "stl" : "";
  const std::string name = "fuzz-input." + hint;
  TriangleMesh mesh;
  try {
    mesh = read_mesh_memory(data + 1, size - 1, name, hint);
  } catch (const Error& e) {
    fuzz::check_names(e, name);
    return 0;
  }
  fuzz::check(!mesh.triangles.empty(), "a mesh read has no triangles");
  for (const auto& t : mesh.triangles) {
    fuzz::check(t[0] < mesh.vertices.size() && t[1] < mesh.vertices.size() && t[2] < mesh.vertices.size(),
                "a triangle read refers to a vertex out of range");
    fuzz::check(t[0] != t[1] && t[1] != t[2] && t[0] != t[2], "a triangle read repeats a corner");
  }
  for (const auto& v : mesh.vertices)
    for (const double x : v) fuzz::check(std::isfinite(x) && std::abs(x) <= 1e6, "a coordinate read is out of range");
  try {
    orient_surface(mesh, name, true);
  } catch (const Error& e) {
    fuzz::check_names(e, name);
    return 0;
  }
  fuzz::check(std::isfinite(enclosed_volume(mesh)), "the volume of a closed mesh is not finite");
  TriangleMesh again = mesh;
  orient_surface(again, name, false);  // any throw is a finding
  fuzz::check(again.triangles == mesh.triangles, "a mesh oriented once was turned again");
  return 0;
}
