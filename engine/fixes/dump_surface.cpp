// dump/surface: the fluid's free surface as a triangle mesh, reconstructed from the particles
// at each frame (engine/surface/surface.hpp: a smoothed particle density, Yu & Turk's
// anisotropic kernels by default, meshed by marching cubes), for ParaView (.vtp, with a .pvd
// collection on the simulated time axis), Blender and Houdini (.ply, .obj; .vdb, a level set).
// The path's extension sets the format; `also` adds others beside it (the same name, another
// extension) from the same mesh. The particles' fields in `fields` (velocity by default) ride on
// the vertices, averaged with the kernels' weights.
//
// The domain's faces that are walls (not periodic, not open) close the surface: the fluid is
// mirrored across them, so the surface meets a wall square at the water's height, and the
// wetted wall is part of the mesh (walls = "closed": a tank's water is one closed body), or
// left out (walls = "open": the free surface alone), or the walls are ignored ("none"). A
// periodic axis's faces cut the surface as walls do, the fluid running on across them. The
// fluid is mirrored across the faces of solids at rest too (`solids`), so the surface meets an
// obstacle or a mesh tank square; it runs on into the solid and closes inside it, hidden.
//
// Sizes are in particle spacings (the lattice spacing of the particles' mass): a voxel of half
// a spacing and a smoothing radius of two resolve the surface at the particles' own scale.
// In a distributed run each rank meshes a slab of the domain, and rank 0 joins and writes.
#include <filesystem>

#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/simulation.hpp"
#include "engine/distributed/comm.hpp"
#include "engine/io/bytes.hpp"
#include "engine/io/surface_files.hpp"
#include "engine/io/vtu.hpp"
#include "engine/output/dump.hpp"
#include "engine/registry/builtin_styles.hpp"
#include "engine/surface/scene_surface.hpp"

namespace pbf {

namespace {

const std::vector<std::string> kFormats = {"vtp", "ply", "obj", "vdb"};

std::string extension_of(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext.empty() ? "" : ext.substr(1);
}

class DumpSurface : public Dump {
 public:
  DumpSurface(const std::string& id, const Params& p)
      : Dump(id, "dump/surface", p),
        voxel_(p.real("voxel")),
        radius_(p.real("radius")),
        iso_(p.real("iso")),
        sphere_radius_(p.real("sphere_radius")),
        smoothing_(static_cast<int>(p.integer("smoothing"))),
        solids_(p.boolean("solids")),
        memory_mib_(p.real("memory")),
        collection_(p.string("collection")) {
    const std::string main = extension_of(pattern());
    if (std::find(kFormats.begin(), kFormats.end(), main) == kFormats.end())
      throw Error(fmt::format("parameter 'path': \"{}\" must end in .vtp, .ply, .obj or .vdb (the format), got \"{}\"",
                              pattern(), main.empty() ? "no extension" : "." + main));
    formats_ = {main};
    for (const std::string& f : p.names("also"))
      if (std::find(formats_.begin(), formats_.end(), f) == formats_.end()) formats_.push_back(f);
    const std::string& kernel = p.string("kernel");
    kernel_ = kernel == "isotropic" ? SurfaceKernel::isotropic
                                    : (kernel == "spheres" ? SurfaceKernel::spheres : SurfaceKernel::anisotropic);
    const std::string& walls = p.string("walls");
    walls_ = walls == "open" ? SurfaceWalls::open : (walls == "none" ? SurfaceWalls::none : SurfaceWalls::closed);
    if (radius_ < voxel_)
      throw Error(fmt::format("parameter 'radius' ({} spacings) must be at least the voxel ({} spacings): a kernel "
                              "narrower than a voxel leaves holes",
                              radius_, voxel_));
    for (const std::string& f : fields().names())
      if (f == "id" || f == "position")
        throw Error(fmt::format("parameter 'fields': \"{}\" is not a value a surface can carry (the vertices have "
                                "their own positions); give fields such as velocity, speed, density",
                                f));
    if (collection_.empty())
      collection_ = (std::filesystem::path(pattern()).parent_path() / (stem("surface") + ".pvd")).string();
  }

  bool runs_distributed() const override { return true; }  // meshed in slabs, joined on rank 0

  void save_state(ByteWriter& w) const override {
    Dump::save_state(w);
    w.put<std::uint64_t>(frames_.size());
    for (const auto& [time, file] : frames_) {
      w.put(time);
      w.put_string(file);
    }
  }

  void restore_state(ByteReader& r) override {
    Dump::restore_state(r);
    const auto count = r.get<std::uint64_t>();
    r.require(count, 2 * sizeof(std::uint64_t));
    frames_.assign(count, {});
    for (auto& [time, file] : frames_) {
      time = r.get<double>();
      file = r.get_string();
    }
  }

 private:
  void write_frame(Simulation& sim, const std::string& path, std::int64_t) override {
    const SurfaceSettings s = settings(sim);
    const SurfaceMesh mesh = scene_surface(sim, fields(), s, solids_);  // collective
    std::filesystem::path base(path);
    const std::string vtp = base.replace_extension(".vtp").string();
    if (std::find(formats_.begin(), formats_.end(), "vtp") != formats_.end()) {
      const auto dir = std::filesystem::path(collection_).parent_path();
      frames_.emplace_back(sim.time(), std::filesystem::path(vtp).lexically_relative(dir.empty() ? "." : dir).string());
    }
    if (!comm::root()) return;
    const std::string comment = fmt::format("pbfengine dump/surface '{}', t = {:.9g} s, step {}", id(), sim.time(), sim.step());
    for (const std::string& format : formats_) {
      const std::string file = std::filesystem::path(path).replace_extension("." + format).string();
      if (format == "vtp") write_surface_vtp(file, mesh);
      else if (format == "ply") write_surface_ply(file, mesh, comment);
      else if (format == "obj") write_surface_obj(file, mesh, comment);
      else write_surface_vdb(file, mesh, s.voxel);
      if (file != path) sim.outputs().wrote(fmt::format("surfaces of fix '{}' (dump/surface, .{})", id(), format), file);
    }
    if (!frames_.empty()) {
      write_pvd(collection_, frames_);
      sim.outputs().wrote(fmt::format("ParaView collection of fix '{}' (dump/surface)", id()), collection_);
    }
  }

  SurfaceSettings settings(Simulation& sim) const {
    SurfaceSettings s = scene_surface_settings(sim, voxel_, radius_);
    s.iso = iso_;
    s.sphere_radius = sphere_radius_ * s.spacing;
    s.smoothing = smoothing_;
    s.kernel = kernel_;
    s.walls = walls_;
    s.memory_limit = memory_mib_ * (1 << 20);
    return s;
  }

  double voxel_, radius_, iso_, sphere_radius_;
  int smoothing_;
  bool solids_;
  double memory_mib_;
  std::string collection_;
  std::vector<std::string> formats_;
  SurfaceKernel kernel_;
  SurfaceWalls walls_;
  std::vector<std::pair<double, std::string>> frames_;  // the .vtp of each frame, for the collection
};

}  // namespace

void register_dump_surface(StyleRegistry& r) {
  auto params = Dump::params("out/surface_*.vtp", {"velocity"});
  params.push_back(ParamSpec{"also", ParamType::StringList, Names{}, "",
                             "more formats of each frame, beside it (same name, their extension)"}.one_of(kFormats));
  params.push_back(ParamSpec{"voxel", ParamType::Real, 0.5, "spacings", "the voxel's edge"}.above_within(0, 100));
  // (A radius of 10 spacings already sums 4,000 neighbours a particle; more is no surface.)
  params.push_back(ParamSpec{"radius", ParamType::Real, 2.0, "spacings", "the smoothing radius R"}.above_within(0, 10));
  params.push_back(ParamSpec{"kernel", ParamType::String, std::string("anisotropic"), "",
                             "the field: anisotropic (Yu & Turk 2013's kernels: flat surfaces, droplets), isotropic "
                             "(a colour field, kernels of radius R) or spheres (Zhu & Bridson 2005's smoothed union "
                             "of spheres)"}.one_of({"anisotropic", "isotropic", "spheres"}));
  params.push_back(ParamSpec{"sphere_radius", ParamType::Real, 0.6, "spacings",
                             "spheres: a particle's radius r (0.6 puts a flat surface half a spacing beyond the "
                             "outer layer)"}.above_within(0, 10));
  params.push_back(ParamSpec{"smoothing", ParamType::Integer, std::int64_t(1), "passes",
                             "of a (1 2 1)/4 filter over the field along each axis: rounds off the particles' "
                             "bumps (droplets are added after it)"}.within(0, 10));
  params.push_back(ParamSpec{"iso", ParamType::Real, 0.5, "",
                             "the surface's level of the smoothed density (1 inside the fluid)"}.above_within(0, 0.99));
  params.push_back(ParamSpec{"walls", ParamType::String, std::string("closed"), "",
                             "the domain's walls: closed (the wetted wall is part of the mesh), open (left out), "
                             "none (ignored)"}.one_of({"closed", "open", "none"}));
  params.push_back({"solids", ParamType::Bool, true, "",
                    "mirror the fluid across the faces of solids at rest, as across the walls (the surface "
                    "meets a solid square, runs on into it and closes there, hidden)"});
  params.push_back(ParamSpec{"memory", ParamType::Real, 4096.0, "MiB",
                             "the most the voxel grid may take: a larger one is refused with its size"}.above(0));
  params.push_back({"collection", ParamType::String, std::string(""), "",
                    "the .pvd collection of the .vtp frames (default: beside them, named after the pattern)"});
  r.add({"dump/surface", StyleKind::fix,
         "the fluid's surface as a triangle mesh (.vtp, .ply, .obj) or level set (.vdb), for ParaView, Blender, Houdini",
         std::move(params), [](const std::string& id, const Params& p) { return std::make_unique<DumpSurface>(id, p); },
         nullptr});
}

}  // namespace pbf
