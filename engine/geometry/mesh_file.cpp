// Reading meshes through Assimp and refusing what the engine cannot use; the placement and
// bounds of a mesh (mesh_file.hpp).
#include "engine/geometry/mesh_file.hpp"

#include <algorithm>
#include <assimp/BaseImporter.h>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <bit>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <utility>
#include <vector>

#include "engine/core/error.hpp"

namespace pbf {

namespace {

constexpr std::size_t kMaxBytes = std::size_t(1) << 30;
// A 1 GiB binary STL holds 21 million triangles; more can only come from instancing (one
// mesh placed by many nodes), which could otherwise fill the memory.
constexpr std::size_t kMaxTriangles = 25'000'000;
constexpr std::size_t kMaxNodes = 1'000'000;
constexpr double kMaxCoordinate = 1e6;  // metres: beyond any scene, likely a wrong unit

using Vec = std::array<double, 3>;

[[noreturn]] void fail(const std::string& name, const std::string& message) {
  throw Error(fmt::format("mesh file '{}': {}", name, message));
}

// The extension as Assimp wants a hint: lowercase letters and digits only, short (Assimp
// refuses a hint over 200 characters, and a name with odd characters would be odd in its
// messages).
std::string clean_hint(const std::string& hint) {
  std::string out;
  for (const char c : hint) {
    if (out.size() == 16) break;
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u)) out += static_cast<char>(std::tolower(u));
  }
  return out;
}

// The bytes as the one file Assimp may open. Not Importer::ReadFileFromMemory: its file
// system serves the bytes for any name that starts with its placeholder, so an OBJ whose
// material library is missing is read again as its own fallback material library
// ("PLACEHOLDER.mtl"), and Assimp 5.2.5's material reader crashes on "mtllib x\nmap_Kd"
// (a texture before any material). Other files (materials, a glTF's .bin) are not found;
// the OBJ reader then goes on without materials, which a solid does not need.
class OneFileIOSystem : public Assimp::IOSystem {
 public:
  OneFileIOSystem(std::string name, const void* data, std::size_t size)
      : name_(std::move(name)), data_(static_cast<const std::uint8_t*>(data)), size_(size) {}
  bool Exists(const char* file) const override { return file && name_ == file; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!Exists(file) || !mode || std::strchr(mode, 'w') || std::strchr(mode, 'a')) return nullptr;
    return new Assimp::MemoryIOStream(data_, size_);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  std::string name_;
  const std::uint8_t* data_;
  std::size_t size_;
};

// Assimp's message, on one short line, calling the file by its name rather than by the
// name Assimp knew it by.
std::string assimp_message(std::string message, const std::string& name, const std::string& internal) {
  for (std::size_t at; (at = message.find(internal)) != std::string::npos;) message.replace(at, internal.size(), name);
  std::replace_if(message.begin(), message.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  while (!message.empty() && (message.back() == ' ' || message.back() == '.')) message.pop_back();
  if (message.size() > 200) message = message.substr(0, 200) + "...";
  return message.empty() ? "no reason given" : message;
}

// An affine map in double precision: rows of [R | t].
using Affine = std::array<std::array<double, 4>, 3>;

Affine compose(const Affine& a, const aiMatrix4x4& m) {
  const double b[3][4] = {{m.a1, m.a2, m.a3, m.a4}, {m.b1, m.b2, m.b3, m.b4}, {m.c1, m.c2, m.c3, m.c4}};
  Affine r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j] + (j == 3 ? a[i][3] : 0.0);
  return r;
}

double determinant(const Affine& a) {
  return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
         a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
}

struct VecHash {
  std::size_t operator()(const Vec& v) const {
    std::uint64_t h = 0;
    for (const double x : v) h = (h ^ std::bit_cast<std::uint64_t>(x)) * 0x100000001b3ull + (h >> 29);
    return static_cast<std::size_t>(h);
  }
};

// Gathers the triangles of every mesh instance into one mesh, joining vertices at the same
// position, and refuses what the rest of the engine cannot use.
class Collector {
 public:
  explicit Collector(const std::string& name) : name_(name) {}

  void add(const aiMesh& mesh, const Affine& to_world) {
    if (!mesh.mVertices || !mesh.mFaces) return;
    if (mesh_.triangles.size() + mesh.mNumFaces > kMaxTriangles)
      fail(name_, fmt::format("more than {} triangles", kMaxTriangles));
    // A mirroring transform turns the triangles inside out: reverse them to undo it.
    const bool mirrored = determinant(to_world) < 0;
    std::vector<std::uint32_t> joined(mesh.mNumVertices, kNone);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3 || !face.mIndices) continue;  // points and lines
      const std::size_t triangle = mesh_.triangles.size() + 1;
      std::array<std::uint32_t, 3> t;
      for (int k = 0; k < 3; ++k) {
        const unsigned v = face.mIndices[k];
        if (v >= mesh.mNumVertices)
          fail(name_, fmt::format("triangle {} refers to vertex {}, but its mesh has {} vertices", triangle, v + 1,
                                  mesh.mNumVertices));
        if (joined[v] == kNone) joined[v] = vertex(transform(to_world, mesh.mVertices[v]), triangle);
        t[k] = joined[v];
      }
      if (mirrored) std::swap(t[1], t[2]);
      mesh_.triangles.push_back(t);
    }
  }

  TriangleMesh finish() {
    if (mesh_.triangles.empty()) fail(name_, "no triangles in it (points and lines are ignored)");
    std::size_t degenerate = 0, first = 0;
    for (std::size_t i = 0; i < mesh_.triangles.size(); ++i) {
      if (!is_degenerate(mesh_.triangles[i])) continue;
      if (degenerate++ == 0) first = i + 1;
    }
    if (degenerate > 0)
      fail(name_, fmt::format("triangle {} has no area (two of its corners coincide or all three lie on a line); "
                              "{} of the {} triangles are so: remove them (a mesh repair tool does) so that every "
                              "triangle has a direction it faces",
                              first, degenerate, mesh_.triangles.size()));
    return std::move(mesh_);
  }

 private:
  static constexpr std::uint32_t kNone = ~std::uint32_t(0);

  static Vec transform(const Affine& a, const aiVector3D& p) {
    Vec r;
    for (int i = 0; i < 3; ++i) r[i] = a[i][0] * p.x + a[i][1] * p.y + a[i][2] * p.z + a[i][3];
    return r;
  }

  std::uint32_t vertex(Vec p, std::size_t triangle) {
    for (double& x : p) {
      if (!std::isfinite(x))
        fail(name_, fmt::format("triangle {} has a vertex coordinate that is not a finite number ({})", triangle, x));
      if (std::abs(x) > kMaxCoordinate)
        fail(name_, fmt::format("triangle {} has a vertex coordinate of {:g} m, beyond the {:g} m any scene may "
                                "span (a file in other units needs a scale)",
                                triangle, x, kMaxCoordinate));
      x += 0.0;  // -0 becomes +0, so both join
    }
    const auto [it, added] = index_.try_emplace(p, static_cast<std::uint32_t>(mesh_.vertices.size()));
    if (added) mesh_.vertices.push_back(p);
    return it->second;
  }

  // Zero area up to rounding: the cross product of two edges is below 1e-12 of the square of
  // the longest edge (an angle of 1e-12 rad). A sliver with any real area is kept.
  bool is_degenerate(const std::array<std::uint32_t, 3>& t) const {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    const Vec &a = mesh_.vertices[t[0]], &b = mesh_.vertices[t[1]], &c = mesh_.vertices[t[2]];
    const Vec u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Vec w{c[0] - b[0], c[1] - b[1], c[2] - b[2]};
    const Vec n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    auto norm2 = [](const Vec& x) { return x[0] * x[0] + x[1] * x[1] + x[2] * x[2]; };
    const double longest2 = std::max({norm2(u), norm2(v), norm2(w)});
    return std::sqrt(norm2(n)) <= 1e-12 * longest2;
  }

  const std::string& name_;
  TriangleMesh mesh_;
  std::unordered_map<Vec, std::uint32_t, VecHash> index_;
};

}  // namespace

TriangleMesh read_mesh_memory(const void* data, std::size_t size, const std::string& name,
                              const std::string& extension_hint) {
  if (size == 0 || !data) fail(name, "the file is empty");
  if (size > kMaxBytes) fail(name, fmt::format("the file has {} bytes, more than the 1 GiB a mesh may have", size));
  const std::string hint = clean_hint(extension_hint);
  const std::string internal = hint.empty() ? "pbf-mesh-input" : "pbf-mesh-input." + hint;
  // Assimp logs only through a DefaultLogger, which the engine never creates: it is silent.
  // Its own vertex joining (aiProcess_JoinIdenticalVertices) is not used: it joins only
  // vertices that agree in normal too, which leaves an STL's corners apart; Collector joins
  // by position, across meshes.
  // Assimp 5.2.5's OpenGEX reader runs strlen past the end of a file without a closing zero
  // (found by fuzz_mesh); files of other or no extensions reach it too, as Assimp asks every
  // reader it has when the extension's reader refuses a file. So it is taken out.
  if (hint == "ogex")
    fail(name, "OpenGEX files are not read (Assimp 5.2.5's reader of them is unsafe): convert it to OBJ or STL");
  Assimp::Importer importer;
  if (const std::size_t ogex = importer.GetImporterIndex("ogex"); ogex != static_cast<std::size_t>(-1)) {
    Assimp::BaseImporter* reader = importer.GetImporter(ogex);
    importer.UnregisterLoader(reader);  // which does not delete it
    delete reader;
  }
  importer.SetIOHandler(new OneFileIOSystem(internal, data, size));  // the importer deletes it
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(internal, aiProcess_Triangulate | aiProcess_SortByPType);
  } catch (const std::exception& e) {  // Assimp catches its own, but not necessarily bad_alloc
    fail(name, fmt::format("not a mesh file that can be read ({})", e.what()));
  }
  if (!scene)
    fail(name, fmt::format("not a mesh file that can be read ({})",
                           assimp_message(importer.GetErrorString(), name, internal)));

  Collector collector(name);
  constexpr Affine kIdentity{{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}};
  std::vector<std::pair<const aiNode*, Affine>> stack;  // iterative: a deep node tree may not overflow the stack
  if (scene->mRootNode) stack.emplace_back(scene->mRootNode, compose(kIdentity, scene->mRootNode->mTransformation));
  for (std::size_t visited = 0; !stack.empty(); ++visited) {
    if (visited == kMaxNodes) fail(name, fmt::format("more than {} nodes in its scene", kMaxNodes));
    const auto [node, to_world] = stack.back();
    stack.pop_back();
    for (unsigned i = 0; i < node->mNumMeshes && node->mMeshes; ++i) {
      const unsigned m = node->mMeshes[i];
      if (m < scene->mNumMeshes && scene->mMeshes && scene->mMeshes[m]) collector.add(*scene->mMeshes[m], to_world);
    }
    // Children in reverse, so that they are visited, and their triangles numbered, in order.
    for (unsigned c = node->mNumChildren; c-- > 0;) {
      const aiNode* child = node->mChildren ? node->mChildren[c] : nullptr;
      if (child) stack.emplace_back(child, compose(to_world, child->mTransformation));
    }
  }
  return collector.finish();
}

TriangleMesh read_mesh_file(const std::string& path) {
  namespace fs = std::filesystem;
  // An ifstream opens a directory and fails only at its first read; a device or a pipe may
  // never end: say what the path is instead.
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) {
    // A script run from another folder than its own is the usual reason: say where a
    // relative path was looked for.
    std::string where;
    if (fs::path(path).is_relative()) {
      const fs::path here = fs::current_path(ec);
      where = fmt::format(": relative paths are taken from the current folder{}", ec ? "" : ", " + here.string());
    }
    throw MissingFile(fmt::format("mesh file '{}' not found{}", path, where), path);
  }
  if (fs::is_directory(status)) fail(path, "cannot be read (it is a directory)");
  if (fs::exists(status) && !fs::is_regular_file(status))
    fail(path, "cannot be read (not a regular file: a device, a pipe or a socket)");
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, fmt::format("cannot be read ({})", errno ? std::strerror(errno) : "cannot open it"));
  const auto size = fs::file_size(path, ec);
  if (ec) fail(path, fmt::format("cannot be read ({})", ec.message()));
  if (size > kMaxBytes) fail(path, fmt::format("the file has {} bytes, more than the 1 GiB a mesh may have", size));
  std::vector<char> bytes(size);
  if (size > 0 && !in.read(bytes.data(), static_cast<std::streamsize>(size)))
    fail(path, "cannot be read (it ended before its size said, or a read failed)");
  return read_mesh_memory(bytes.data(), bytes.size(), path, fs::path(path).extension().string());
}


// ---- what is done with a mesh read ----

namespace {

// sin and cos of an angle in degrees, exact at multiples of 90 (so a quarter turn keeps a
// box's faces on the axes exactly).
std::pair<double, double> sin_cos_deg(double deg) {
  const double r = std::fmod(deg, 360.0);
  if (r == std::round(r / 90) * 90) {
    static constexpr double kSin[] = {0, 1, 0, -1}, kCos[] = {1, 0, -1, 0};
    const int q = ((static_cast<int>(std::round(r / 90)) % 4) + 4) % 4;
    return {kSin[q], kCos[q]};
  }
  const double rad = r * (std::numbers::pi / 180);
  return {std::sin(rad), std::cos(rad)};
}

}  // namespace

std::array<double, 9> rotation_matrix(const std::array<double, 3>& rotate_deg) {
  const auto [sx, cx] = sin_cos_deg(rotate_deg[0]);
  const auto [sy, cy] = sin_cos_deg(rotate_deg[1]);
  const auto [sz, cz] = sin_cos_deg(rotate_deg[2]);
  const std::array<double, 9> rx{1, 0, 0, 0, cx, -sx, 0, sx, cx}, ry{cy, 0, sy, 0, 1, 0, -sy, 0, cy},
      rz{cz, -sz, 0, sz, cz, 0, 0, 0, 1};
  auto times = [](const std::array<double, 9>& a, const std::array<double, 9>& b) {
    std::array<double, 9> r{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
    return r;
  };
  return times(rz, times(ry, rx));
}

void place(TriangleMesh& mesh, const Placement& placement) {
  const auto r = rotation_matrix(placement.rotate_deg);
  const auto& s = placement.scale;
  const auto& t = placement.translate;
  for (auto& v : mesh.vertices) {
    const Vec p{s[0] * v[0], s[1] * v[1], s[2] * v[2]};
    for (int i = 0; i < 3; ++i) v[i] = r[3 * i] * p[0] + r[3 * i + 1] * p[1] + r[3 * i + 2] * p[2] + t[i];
  }
  // A mirroring scale (an odd number of negative factors) turns the surface inside out.
  if (s[0] * s[1] * s[2] < 0)
    for (auto& tri : mesh.triangles) std::swap(tri[1], tri[2]);
}

std::array<std::array<double, 3>, 2> bounds(const TriangleMesh& mesh) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::array<std::array<double, 3>, 2> b{{{inf, inf, inf}, {-inf, -inf, -inf}}};
  for (const auto& v : mesh.vertices)
    for (int d = 0; d < 3; ++d) {
      b[0][d] = std::min(b[0][d], v[d]);
      b[1][d] = std::max(b[1][d], v[d]);
    }
  return b;
}

}  // namespace pbf
