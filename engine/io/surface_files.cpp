#include "engine/io/surface_files.hpp"

#include <cstring>

#include <fmt/format.h>

#include "engine/io/atomic_file.hpp"
#include "engine/io/vtp.hpp"

namespace pbf {

namespace {

// An attribute's name for component c: NAME for a scalar, NAME_x, NAME_y, NAME_z for a vector.
std::string component_name(const SurfaceCloud::Attribute& a, int c) {
  if (a.components == 1) return a.name;
  if (a.components == 3) return fmt::format("{}_{}", a.name, "xyz"[c]);
  return fmt::format("{}_{}", a.name, c);
}

}  // namespace

void write_surface_vtp(const std::string& path, const SurfaceMesh& mesh) {
  const std::size_t nv = mesh.mesh.vertices.size();
  std::vector<std::vector<double>> interleaved;
  std::vector<VtuArray> arrays;
  arrays.push_back({"Normals", 3, VtuType::Float32, mesh.normals.data()});
  for (const auto& a : mesh.attributes) {
    auto& values = interleaved.emplace_back(nv * static_cast<std::size_t>(a.components));
    for (std::size_t v = 0; v < nv; ++v)
      for (int c = 0; c < a.components; ++c) values[v * a.components + c] = a.values[c * nv + v];
  }
  for (std::size_t k = 0; k < mesh.attributes.size(); ++k)
    arrays.push_back({mesh.attributes[k].name, mesh.attributes[k].components, VtuType::Float64, interleaved[k].data()});
  write_vtp(path, mesh.mesh, arrays, "Normals");
}

void write_surface_ply(const std::string& path, const SurfaceMesh& mesh, const std::string& comment) {
  const std::size_t nv = mesh.mesh.vertices.size(), nt = mesh.mesh.triangles.size();
  std::string head = "ply\nformat binary_little_endian 1.0\n";
  if (!comment.empty()) head += "comment " + comment + "\n";
  head += fmt::format("element vertex {}\n", nv);
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) head += fmt::format("property float {}\n", p);
  int columns = 6;
  for (const auto& a : mesh.attributes)
    for (int c = 0; c < a.components; ++c, ++columns) head += fmt::format("property float {}\n", component_name(a, c));
  head += fmt::format("element face {}\nproperty list uchar int vertex_indices\nend_header\n", nt);
  AtomicFile out(path);
  out.write(head);
  // Vertices and faces in chunks, as x86 stores them (little-endian).
  constexpr std::size_t kChunk = 4096;
  std::vector<float> row(kChunk * static_cast<std::size_t>(columns));
  for (std::size_t v0 = 0; v0 < nv; v0 += kChunk) {
    const std::size_t m = std::min(kChunk, nv - v0);
    for (std::size_t k = 0; k < m; ++k) {
      float* r = &row[k * static_cast<std::size_t>(columns)];
      const std::size_t v = v0 + k;
      for (int c = 0; c < 3; ++c) r[c] = static_cast<float>(mesh.mesh.vertices[v][c]), r[3 + c] = mesh.normals[v][c];
      int at = 6;
      for (const auto& a : mesh.attributes)
        for (int c = 0; c < a.components; ++c) r[at++] = static_cast<float>(a.values[c * nv + v]);
    }
    out.write(row.data(), m * static_cast<std::size_t>(columns) * sizeof(float));
  }
  std::vector<char> faces(kChunk * 13);
  for (std::size_t t0 = 0; t0 < nt; t0 += kChunk) {
    const std::size_t m = std::min(kChunk, nt - t0);
    for (std::size_t k = 0; k < m; ++k) {
      char* f = &faces[k * 13];
      f[0] = 3;
      for (int c = 0; c < 3; ++c) {
        const std::int32_t index = static_cast<std::int32_t>(mesh.mesh.triangles[t0 + k][c]);
        std::memcpy(f + 1 + 4 * c, &index, 4);
      }
    }
    out.write(faces.data(), m * 13);
  }
  out.commit();
}

void write_surface_obj(const std::string& path, const SurfaceMesh& mesh, const std::string& comment) {
  AtomicFile out(path);
  fmt::memory_buffer text;
  if (!comment.empty()) fmt::format_to(std::back_inserter(text), "# {}\n", comment);
  auto flush = [&](bool always) {
    if (always || text.size() > (1 << 20)) {
      out.write(text.data(), text.size());
      text.clear();
    }
  };
  for (const auto& x : mesh.mesh.vertices) {
    fmt::format_to(std::back_inserter(text), "v {:.7g} {:.7g} {:.7g}\n", x[0], x[1], x[2]);
    flush(false);
  }
  for (const auto& n : mesh.normals) {
    fmt::format_to(std::back_inserter(text), "vn {:.4f} {:.4f} {:.4f}\n", n[0], n[1], n[2]);
    flush(false);
  }
  for (const auto& t : mesh.mesh.triangles) {  // OBJ counts from 1
    fmt::format_to(std::back_inserter(text), "f {0}//{0} {1}//{1} {2}//{2}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    flush(false);
  }
  flush(true);
  out.commit();
}

}  // namespace pbf
