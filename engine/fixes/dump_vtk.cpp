// dump/vtk: one VTK XML unstructured grid (.vtu) per frame, binary appended data, and a
// ParaView collection (.pvd) listing every frame with its simulated time, so ParaView opens
// the whole run as an animation on the right time axis. Positions are the points; the
// chosen fields are point data, in id order.
//
// A distributed run writes each frame as pieces, one per rank with its particles in id order
// (frame_00003_R.vtu), and a parallel file that names them (frame_00003.pvtu), which the
// collection lists instead.
//
// Solids go beside the frames as surfaces (.vtp), each written only when it has moved: out/
// frame_*.vtu gives out/frame_solid_NAME.vtp for a surface that never moved (version 0) and
// out/frame_solid_NAME_NNNNN.vtp (the frame number) for each new position of a moving one
// (and for a solid replaced by another of the same name between runs).
// The collection lists, at every frame's time, the particles as part 0 and each solid's
// current surface as parts 1, 2, ..., so ParaView shows fluid and solids together.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/io/bytes.hpp"
#include "engine/output/dump.hpp"
#include "engine/fixes/solid_dynamics.hpp"
#include "engine/io/vtp.hpp"
#include "engine/io/vtu.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"

namespace pbf {

namespace {

constexpr VtuType kRealType = sizeof(real) == 4 ? VtuType::Float32 : VtuType::Float64;

// FNV-1a of a surface's bytes: tells, at the start of a run, whether a solid of the same name
// and version is the surface already on disk (a solid replaced between runs keeps its name).
std::uint64_t fingerprint(const TriangleMesh& mesh) {
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) h = (h ^ p[k]) * 1099511628211ull;
  };
  mix(mesh.vertices.data(), mesh.vertices.size() * sizeof(mesh.vertices[0]));
  mix(mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
  return h;
}

// A solid's name as part of a file name (fix ids are letters, digits, '_' and '-' already).
std::string file_name_part(const std::string& name) {
  std::string s = name.empty() ? "solid" : name;
  for (char& c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) c = '_';
  return s;
}

class DumpVtk : public Dump {
 public:
  DumpVtk(const std::string& id, const Params& p) : Dump(id, "dump/vtk", p), collection_(p.string("collection")) {
    // out/frame_*.vtu -> "frame": names the collection (out/frame.pvd) and the solids' files.
    stem_ = stem("frames");
    if (collection_.empty()) collection_ = (std::filesystem::path(pattern()).parent_path() / (stem_ + ".pvd")).string();
  }

  bool runs_distributed() const override { return true; }  // a piece per rank and a .pvtu

  void init(Simulation& sim) override {
    check_surfaces_ = true;  // the pipeline may have changed since the last run
    Dump::init(sim);
  }

  // The frames (time and particle file) as before solids existed, then the solids' part:
  // their files per frame and what was last written of each. A restart of a version without
  // solids ends after the frames, and continues with none written.
  void save_state(ByteWriter& w) const override {
    Dump::save_state(w);
    w.put<std::uint64_t>(frames_.size());
    for (const auto& frame : frames_) {
      w.put(frame.time);
      w.put_string(frame.files[0]);
    }
    w.put<std::uint64_t>(frames_.size());
    for (const auto& frame : frames_) {
      w.put<std::uint64_t>(frame.files.size() - 1);
      for (std::size_t k = 1; k < frame.files.size(); ++k) w.put_string(frame.files[k]);
    }
    w.put<std::uint64_t>(surfaces_.size());
    for (const auto& s : surfaces_) {
      w.put_string(s.name);
      w.put(s.version);
      w.put(s.fingerprint);
      w.put_string(s.file);
    }
  }

  void restore_state(ByteReader& r) override {
    Dump::restore_state(r);
    const auto count = r.get<std::uint64_t>();
    r.require(count, 2 * sizeof(std::uint64_t));
    frames_.assign(count, {});
    for (auto& frame : frames_) {
      frame.time = r.get<double>();
      frame.files = {r.get_string()};
    }
    surfaces_.clear();
    if (r.left() == 0) return;
    if (r.get<std::uint64_t>() != count)
      throw Error(fmt::format("{}: the solids' files do not match the frames", r.what()));
    for (auto& frame : frames_) {
      const auto parts = r.get<std::uint64_t>();
      r.require(parts, sizeof(std::uint64_t));
      for (std::uint64_t k = 0; k < parts; ++k) frame.files.push_back(r.get_string());
    }
    const auto surfaces = r.get<std::uint64_t>();
    r.require(surfaces, 4 * sizeof(std::uint64_t));
    surfaces_.resize(surfaces);
    for (auto& s : surfaces_) {
      s.name = r.get_string();
      s.version = r.get<std::uint64_t>();
      s.fingerprint = r.get<std::uint64_t>();
      s.file = r.get_string();
    }
  }

 private:
  void write_frame(Simulation& sim, const std::string& path, std::int64_t frame) override {
    // A distributed run: each rank's particles in a piece of its own, tied together by a .pvtu
    // (rank 0's), which the collection lists.
    const std::string frame_file = sim.particles().distributed() ? write_pieces(sim, path) : write_whole(sim, path);

    // The collection names files relative to its own directory, as ParaView expects.
    const auto base = std::filesystem::path(collection_).parent_path();
    auto relative = [&](const std::string& file) {
      return std::filesystem::path(file).lexically_relative(base.empty() ? "." : base).string();
    };
    Frame& f = frames_.emplace_back(Frame{sim.time(), {relative(frame_file)}});
    for (const SolidBody* solid : sim.solid_bodies())
      f.files.push_back(relative(surface_file(*solid, std::filesystem::path(path).parent_path(), frame)));
    check_surfaces_ = false;

    if (!comm::root()) return;  // every rank keeps the same list; rank 0 writes it
    std::vector<PvdDataSet> datasets;
    for (const auto& fr : frames_)
      for (std::size_t k = 0; k < fr.files.size(); ++k) datasets.push_back({fr.time, static_cast<int>(k), fr.files[k]});
    write_pvd(collection_, datasets);
    sim.outputs().wrote(fmt::format("ParaView collection of fix '{}' (dump/vtk)", id()), collection_);
  }

  // One process: every particle, in id order.
  std::string write_whole(Simulation& sim, const std::string& path) {
    const std::size_t n = sim.particles().size();
    values_.resize(fields().size());
    std::vector<VtuArray> arrays;
    for (std::size_t k = 0; k < fields().size(); ++k) {
      if (fields().is_id(k)) {
        fields().gather_ids(sim, ids_);
        arrays.push_back({"id", 1, VtuType::Int64, ids_.data()});
      } else {
        fields().gather(sim, k, values_[k]);
        arrays.push_back({fields().names()[k], fields().components(k), kRealType, values_[k].data()});
      }
    }
    DumpFields position({"position"});
    position.resolve(sim);
    position.gather(sim, 0, points_);
    write_vtu(path, n, {"Points", 3, kRealType, points_.data()}, arrays);
    return path;
  }

  // A distributed run: out/frame_00003.vtu becomes out/frame_00003.pvtu and the pieces
  // out/frame_00003_R.vtu, one per rank, each with that rank's particles in id order.
  std::string write_pieces(Simulation& sim, const std::string& path) {
    sim.refresh_neighbors();  // derived fields read neighbours: the ghosts first (they move the arrays)
    const auto& P = sim.particles();
    const std::size_t n = P.size();
    std::vector<std::uint32_t> by_id(n);
    for (std::size_t i = 0; i < n; ++i) by_id[i] = static_cast<std::uint32_t>(i);
    std::sort(by_id.begin(), by_id.end(), [&](std::uint32_t a, std::uint32_t b) { return P.ids()[a] < P.ids()[b]; });
    auto ordered = [&](const std::vector<const real*>& columns, std::vector<real>& out) {
      const std::size_t nc = columns.size();
      out.resize(n * nc);
      for (std::size_t i = 0; i < n; ++i)
        for (std::size_t c = 0; c < nc; ++c) out[i * nc + c] = columns[c][by_id[i]];
    };
    values_.resize(fields().size());
    std::vector<VtuArray> arrays;
    for (std::size_t k = 0; k < fields().size(); ++k) {
      if (fields().is_id(k)) {
        ids_.resize(n);
        for (std::size_t i = 0; i < n; ++i) ids_[i] = P.ids()[by_id[i]];
        arrays.push_back({"id", 1, VtuType::Int64, ids_.data()});
      } else {
        ordered(fields().columns(sim, k), values_[k]);
        arrays.push_back({fields().names()[k], fields().components(k), kRealType, values_[k].data()});
      }
    }
    ordered({P.x(), P.y(), P.z()}, points_);
    const std::filesystem::path whole(path);
    const std::string stem = (whole.parent_path() / whole.stem()).string();
    auto piece = [&](int rank) { return fmt::format("{}_{}.vtu", stem, rank); };
    write_vtu(piece(comm::rank()), n, {"Points", 3, kRealType, points_.data()}, arrays);
    const std::string parallel = stem + ".pvtu";
    comm::barrier();  // every piece is there before the file that names them
    if (comm::root()) {
      std::vector<std::string> pieces;
      for (int r = 0; r < comm::ranks(); ++r) pieces.push_back(std::filesystem::path(piece(r)).filename().string());
      write_pvtu(parallel, kRealType, arrays, pieces);
    }
    return parallel;
  }

  // The file that holds the solid's surface now: the one last written, unless the surface
  // has moved since (a new version; at the start of a run, also other bytes under the same
  // name and version), in which case it is written now.
  std::string surface_file(const SolidBody& solid, const std::filesystem::path& dir, std::int64_t frame) {
    const std::string name = file_name_part(solid.name());
    const std::uint64_t version = solid.surface_version();
    auto it = std::find_if(surfaces_.begin(), surfaces_.end(), [&](const Surface& s) { return s.name == name; });
    if (it != surfaces_.end() && it->version == version &&
        !(check_surfaces_ && it->fingerprint != fingerprint(solid.surface())))
      return it->file;
    // A surface replaced under the same name gets a numbered file too: earlier frames keep theirs.
    const bool first = it == surfaces_.end();
    const std::string file = (dir / (version == 0 && first ? fmt::format("{}_solid_{}.vtp", stem_, name)
                                                           : fmt::format("{}_solid_{}_{:05d}.vtp", stem_, name, frame)))
                                 .string();
    if (comm::root()) {  // a distributed run's are rank 0's to write
      std::vector<Point> velocity;  // a body's: its points' velocities
      if (const SolidDynamics* body = solid.dynamics())
        for (const Point& p : solid.surface().vertices) velocity.push_back(body->body().velocity_at(p));
      write_vtp(file, solid.surface(), solid.dynamics() ? &velocity : nullptr);
    }
    if (first) it = surfaces_.insert(surfaces_.end(), Surface{});
    *it = Surface{name, version, fingerprint(solid.surface()), file};
    return file;
  }

  struct Frame {
    double time;
    std::vector<std::string> files;  // the particles, then each solid's surface (parts 0, 1, ...)
  };
  struct Surface {  // the surface file last written of a solid
    std::string name;
    std::uint64_t version, fingerprint;
    std::string file;
  };

  std::string collection_, stem_;
  std::vector<Frame> frames_;      // every frame so far
  std::vector<Surface> surfaces_;  // by solid name, in the order first written
  bool check_surfaces_ = true;
  std::vector<std::vector<real>> values_;
  std::vector<real> points_;
  std::vector<std::int64_t> ids_;
};

}  // namespace

void register_dump_vtk(StyleRegistry& r) {
  auto params = Dump::params("out/frame_*.vtu", {"id", "velocity", "speed", "density"});
  params.push_back({"collection", ParamType::String, std::string(""), "",
                    "the .pvd collection file (default: beside the frames, named after the pattern)"});
  r.add({"dump/vtk", StyleKind::fix,
         "VTK XML frames (.vtu, binary), solids' surfaces (.vtp) and a .pvd collection with their times, for ParaView",
         std::move(params), [](const std::string& id, const Params& p) { return std::make_unique<DumpVtk>(id, p); },
         nullptr});
}

}  // namespace pbf
