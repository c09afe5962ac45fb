#include "engine/surface/scene_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/geometry/solid_body.hpp"
#include "engine/io/bytes.hpp"
#include "engine/sph/mass.hpp"

namespace pbf {

SurfaceSettings scene_surface_settings(Simulation& sim, double voxel_spacings, double radius_spacings) {
  SurfaceSettings s;
  const double mass = sim.particle_mass();  // collective
  s.spacing = mass > 0 ? lattice_spacing(mass, sim.kernels(), sim.rest_density()) : sim.kernel_radius() / 2;
  s.mass = mass;
  s.radius = radius_spacings * s.spacing;
  s.voxel = voxel_spacings * s.spacing;
  s.sphere_radius = 0.6 * s.spacing;
  const Domain& d = sim.domain();
  for (int a = 0; a < 3; ++a) {
    s.lo[a] = d.lo[a], s.hi[a] = d.hi[a];
    // (A periodic face closes the surface too; its images are the fluid beyond it.)
    for (int side = 0; side < 2; ++side) s.wall[2 * a + side] = d.periodic[a] || !d.open[2 * a + side];
    s.periodic[a] = d.periodic[a];
  }
  return s;
}

namespace {

// Each particle's record: id, x, y, z, mass, the solid face it is mirrored across (its normal
// and the distance to it, -1 for none), then each field's components.
constexpr std::size_t kFields = 9;
struct Records {
  std::size_t width = kFields;
  std::vector<double> values;
  std::vector<std::string> names;
  std::vector<int> components;
  std::size_t size() const { return values.size() / width; }
};

// The nearest face of a solid at rest within R of a particle at x, where the solid is thick
// enough for the mirrored fluid (the image's kernel, 2 d + R behind the particle, ends in the
// wall) and the face is not one of the domain's walls (which the surface mirrors itself).
bool solid_face(const std::vector<const SolidBody*>& solids, const SurfaceSettings& s, const std::array<double, 3>& x,
                double& distance, std::array<double, 3>& normal) {
  bool found = false;
  for (const SolidBody* solid : solids) {
    double d;
    std::array<double, 3> n;
    if (!solid->face_near(x, d, n) || !(d >= 0 && d < s.radius) || (found && d >= distance)) continue;
    bool domain_wall = false;
    for (int a = 0; a < 3; ++a) {
      if (std::fabs(n[a]) < 0.99) continue;
      const double face = x[a] - d * n[a];
      domain_wall |= n[a] > 0 ? s.wall[2 * a] && std::fabs(face - s.lo[a]) < s.spacing / 4
                              : s.wall[2 * a + 1] && std::fabs(face - s.hi[a]) < s.spacing / 4;
    }
    if (domain_wall) continue;
    const double behind = 2 * d + s.radius;
    const auto depth = solid->depth_in_wall({x[0] - behind * n[0], x[1] - behind * n[1], x[2] - behind * n[2]});
    if (!depth || !(*depth > 0)) continue;
    found = true, distance = d, normal = n;
  }
  return found;
}

Records local_records(Simulation& sim, DumpFields& fields, const SurfaceSettings& settings, bool solids) {
  if (sim.particles().distributed()) sim.refresh_neighbors();  // derived fields read neighbours
  const auto& P = sim.particles();
  const std::size_t n = P.size();
  Records r;
  std::vector<std::vector<const real*>> columns;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    columns.push_back(fields.columns(sim, k));
    r.names.push_back(fields.names()[k]);
    r.components.push_back(static_cast<int>(columns.back().size()));
    r.width += columns.back().size();
  }
  r.values.resize(n * r.width);
  for (std::size_t i = 0; i < n; ++i) {
    double* row = &r.values[i * r.width];
    row[0] = static_cast<double>(P.ids()[i]), row[1] = P.x()[i], row[2] = P.y()[i], row[3] = P.z()[i];
    row[4] = P.mass()[i];
    double distance = -1;
    std::array<double, 3> normal{};
    if (solids && settings.walls != SurfaceWalls::none)
      solid_face(sim.solid_bodies(), settings, {row[1], row[2], row[3]}, distance, normal);
    row[5] = normal[0], row[6] = normal[1], row[7] = normal[2], row[8] = distance;
    std::size_t at = kFields;
    for (const auto& field : columns)
      for (const real* c : field) row[at++] = c[i];
  }
  return r;
}

// The records (`values`, `width` each) as a cloud, in id order.
SurfaceCloud cloud_of(const Records& shape, const std::vector<double>& values, const SurfaceSettings& settings) {
  const std::size_t width = shape.width, total = values.size() / width;
  std::vector<std::size_t> order(total);
  for (std::size_t i = 0; i < total; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return values[a * width] < values[b * width]; });
  SurfaceCloud c;
  c.x.resize(total), c.y.resize(total), c.z.resize(total), c.volume.resize(total);
  const double unit = settings.spacing * settings.spacing * settings.spacing / (settings.mass > 0 ? settings.mass : 1);
  for (std::size_t k = 0; k < shape.names.size(); ++k)
    c.attributes.push_back({shape.names[k], shape.components[k],
                            std::vector<double>(total * static_cast<std::size_t>(shape.components[k]))});
  for (std::size_t i = 0; i < total; ++i) {
    const double* r = &values[order[i] * width];
    c.x[i] = static_cast<real>(r[1]), c.y[i] = static_cast<real>(r[2]), c.z[i] = static_cast<real>(r[3]);
    c.volume[i] = r[4] * unit;
    if (r[8] >= 0) c.mirrors.push_back({static_cast<std::uint32_t>(i), {r[5], r[6], r[7]}, r[8]});
    std::size_t at = kFields;
    for (auto& a : c.attributes)
      for (int comp = 0; comp < a.components; ++comp) a.values[static_cast<std::size_t>(comp) * total + i] = r[at++];
  }
  return c;
}

// Every rank's `bytes` to every rank, in rank order (through rank 0).
std::vector<std::vector<char>> everyones(const std::vector<char>& bytes) {
  const auto gathered = comm::gather_bytes(bytes);
  ByteWriter w;
  for (const auto& g : gathered) {
    w.put<std::uint64_t>(g.size());
    w.put_array(g.data(), g.size());
  }
  std::vector<char> all(w.bytes().begin(), w.bytes().end());
  comm::broadcast(all);
  ByteReader r(reinterpret_cast<const unsigned char*>(all.data()), all.size(), "the ranks' surface blocks");
  std::vector<std::vector<char>> out(static_cast<std::size_t>(comm::ranks()));
  for (auto& o : out) r.get_array(o, r.get<std::uint64_t>());
  return out;
}

// The first rank's error (empty: none), on every rank.
std::string first_error(const std::string& mine) {
  for (const auto& e : everyones(std::vector<char>(mine.begin(), mine.end())))
    if (!e.empty()) return std::string(e.begin(), e.end());
  return {};
}

void put_piece(ByteWriter& w, const SurfacePiece& p) {
  auto vector = [&](const auto& v) {
    w.put<std::uint64_t>(v.size());
    w.put_array(v.data(), v.size());
  };
  vector(p.blocks), vector(p.first_vertex), vector(p.first_triangle), vector(p.keys), vector(p.vertices);
  vector(p.normals), vector(p.on_wall), vector(p.corners);
  for (const auto& a : p.attributes) vector(a.values);
}

SurfacePiece get_piece(ByteReader& r, const SurfaceCloud& shape) {
  SurfacePiece p;
  auto vector = [&](auto& v) { r.get_array(v, r.get<std::uint64_t>()); };
  vector(p.blocks), vector(p.first_vertex), vector(p.first_triangle), vector(p.keys), vector(p.vertices);
  vector(p.normals), vector(p.on_wall), vector(p.corners);
  for (const auto& a : shape.attributes) {
    p.attributes.push_back({a.name, a.components, {}});
    vector(p.attributes.back().values);
  }
  return p;
}

// A distributed run: each rank meshes a slab of blocks across the domain's longest axis, with
// about as many particles as the others, from its particles and those within reach of the
// slab (SurfaceSlabs::needs); rank 0 joins the pieces.
SurfaceMesh distributed_surface(const Records& mine, const SurfaceSettings& s) {
  const std::size_t n = mine.size(), width = mine.width;
  {  // the particles checked here, so that every rank stops together
    const SurfaceCloud local = cloud_of(mine, mine.values, s);
    std::string error;
    try {
      check_surface_input(local, s);
    } catch (const Error& e) {
      error = e.what();
    }
    error = first_error(error);
    if (!error.empty()) throw Error(error);
  }
  std::int64_t mirrored = 0;
  for (std::size_t i = 0; i < n; ++i) mirrored += mine.values[i * width + 8] >= 0;
  SurfaceSlabs slabs(s, comm::sum(mirrored) > 0);
  std::vector<std::int64_t> count(static_cast<std::size_t>(slabs.layers), 0);
  for (std::size_t i = 0; i < n; ++i) ++count[static_cast<std::size_t>(slabs.layer(mine.values[i * width + 1 + slabs.axis]))];
  comm::sum(count);
  const int ranks = comm::ranks();
  slabs.cut(count, ranks);
  // Each particle to every rank whose slab it reaches.
  std::vector<std::vector<char>> send(static_cast<std::size_t>(ranks)), received;
  for (std::size_t i = 0; i < n; ++i)
    for (int r = 0; r < ranks; ++r)
      if (slabs.needs(r, mine.values[i * width + 1 + slabs.axis])) {
        const char* row = reinterpret_cast<const char*>(&mine.values[i * width]);
        send[static_cast<std::size_t>(r)].insert(send[static_cast<std::size_t>(r)].end(), row, row + width * sizeof(double));
      }
  comm::all_to_all_bytes(send, received);
  send.clear();
  std::vector<double> values;
  for (const auto& bytes : received) {
    const std::size_t old = values.size();
    values.resize(old + bytes.size() / sizeof(double));
    std::memcpy(values.data() + old, bytes.data(), bytes.size());
  }
  received.clear();
  const SurfaceCloud cloud = cloud_of(mine, values, s);
  values.clear();

  SurfacePart part = slabs.part(comm::rank());
  bool agreed_error = false;
  part.agree = [&](std::vector<std::int64_t>& blocks, std::string& error) {
    ByteWriter w;
    w.put_string(error);
    w.put<std::uint64_t>(blocks.size());
    w.put_array(blocks.data(), blocks.size());
    blocks.clear();
    error.clear();
    for (const auto& bytes : everyones(std::vector<char>(w.bytes().begin(), w.bytes().end()))) {
      ByteReader r(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "a rank's surface blocks");
      const std::string e = r.get_string();
      if (error.empty()) error = e;
      std::vector<std::int64_t> theirs;
      r.get_array(theirs, r.get<std::uint64_t>());
      blocks.insert(blocks.end(), theirs.begin(), theirs.end());
    }
    agreed_error = !error.empty();
  };
  // The pieces to rank 0, or the error a rank met after the agreed rounds.
  ByteWriter w;
  try {
    const SurfacePiece piece = reconstruct_surface_part(cloud, s, part);
    w.put_string("");
    put_piece(w, piece);
  } catch (const Error& e) {
    if (agreed_error) throw;
    w = ByteWriter();
    w.put_string(e.what());
  }
  const auto gathered =
      comm::gather_bytes(std::span<const char>(reinterpret_cast<const char*>(w.bytes().data()), w.bytes().size()));
  std::vector<SurfacePiece> pieces;
  std::string error;
  for (const auto& bytes : gathered) {
    ByteReader r(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), "a rank's surface piece");
    const std::string e = r.get_string();
    if (!e.empty() && error.empty()) error = e;
    if (e.empty()) pieces.push_back(get_piece(r, cloud));
  }
  std::vector<char> verdict(error.begin(), error.end());
  comm::broadcast(verdict);
  if (!verdict.empty()) throw Error(std::string(verdict.begin(), verdict.end()));
  if (!comm::root()) return {};
  return join_surface_pieces(pieces, s);
}

}  // namespace

SurfaceMesh scene_surface(Simulation& sim, DumpFields& fields, const SurfaceSettings& settings, bool solids) {
  const Records mine = local_records(sim, fields, settings, solids);
  if (sim.particles().distributed()) return distributed_surface(mine, settings);
  return reconstruct_surface(cloud_of(mine, mine.values, settings), settings);
}

}  // namespace pbf
