// The simulation (engine/core/simulation.hpp): the scene's settings, the pipeline, the density
// service and the scratch arrays; the neighbour lists and the ghosts are in simulation_neighbors.cpp.
#include "engine/core/simulation.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>

#include <spdlog/spdlog.h>

#include "engine/core/error.hpp"
#include "engine/core/parallel.hpp"
#include "engine/io/bytes.hpp"
#include "engine/sph/pair_sums.hpp"
#include "engine/sph/resolution.hpp"

namespace pbf {

Simulation::Simulation() = default;
Simulation::~Simulation() = default;

namespace {
// A period shorter than 2 h would put a particle within h of two images of another (or of
// its own), and the grid's cells in one period would be fewer than two.
void check_periodic_lengths(const Domain& domain, double h) {
  for (int a = 0; a < 3; ++a)
    if (domain.periodic[a] && domain.extent(a) < 2 * h)
      throw Error(fmt::format("domain: the periodic axis {} is {:.6g} m long, shorter than two kernel radii (2 h = "
                              "{:.6g} m): a particle would meet its own image; lengthen the domain along {}, or make "
                              "{} not periodic",
                              "xyz"[a], domain.extent(a), 2 * h, "xyz"[a], "xyz"[a]));
}
}  // namespace

void Simulation::set_domain(const Domain& domain) {
  for (int a = 0; a < 3; ++a)
    if (!(domain.hi[a] > domain.lo[a]) || !std::isfinite(domain.hi[a] - domain.lo[a]))
      throw Error(fmt::format("domain: hi must exceed lo along every axis (axis {}: lo {}, hi {})", "xyz"[a],
                              domain.lo[a], domain.hi[a]));
  if (h_ > 0) check_periodic_lengths(domain, h_);
  domain_ = domain;
  domain_set_ = true;
  positions_changed();
}

void Simulation::set_kernel_radius(double h) {
  if (!(h > 0) || !std::isfinite(h)) throw Error(fmt::format("kernel radius h must be positive, got {}", h));
  const Kernels kernels(h);
  const real gradient_coef = kernels.coef * kernels.inv_h * kernels.inv_h;
  if (!std::isfinite(kernels.coef) || !(kernels.coef > 0) || !std::isfinite(gradient_coef) || !(gradient_coef > 0) ||
      !(kernels.h2 > 0))
    throw Error(fmt::format("kernel radius h = {} m: the kernel's coefficients (21 / (2 pi h^3), over h^2 for the "
                            "gradient) are beyond the {} "
                            "precision of the particle data; choose a unit in which h is nearer 1",
                            h, sizeof(real) == 4 ? "single" : "double"));
  // Particles made for another h (pbf.kernel_radius after pbf.lattice): checked against it now.
  const auto& P = particles_;
  if (P.size() > 1) check_kernel_radius(h, sampled_spacing(P.x(), P.y(), P.z(), P.size()), "pbf.kernel_radius");
  check_periodic_lengths(domain_, h);
  h_ = h;
  kernels_ = kernels;
  positions_changed();
}

void Simulation::set_timestep(double dt) {
  if (!(dt > 0) || !std::isfinite(dt)) throw Error(fmt::format("time step must be positive, got {}", dt));
  // time() = time_base_ + (step - step_base_) dt: exact multiples of dt, no drift.
  time_base_ = time();
  step_base_ = step_;
  dt_ = dt;
}

void Simulation::set_rest_density(double rho0) {
  // The densest liquid, mercury, is 13,546 kg/m^3: 1e5 leaves room for any fluid in SI units.
  if (!(rho0 > 0 && rho0 <= 1e5))
    throw Error(fmt::format("rest density must be in (0, 1e5] kg/m^3, got {}", rho0));
  rest_density_ = rho0;
}

void Simulation::check_scale() const {
  check_periodic_lengths(domain_, h_);
  constexpr double kMostRadii = 1e6;
  for (int a = 0; a < 3; ++a) {
    const double reach = std::max(std::fabs(domain_.lo[a]), std::fabs(domain_.hi[a]));
    if (reach > kMostRadii * h_)
      throw Error(fmt::format("the domain reaches {:.3g} m from the origin along {}, {:.3g} kernel radii (h = {:.3g} m): "
                              "more than {:.0e}, where positions no longer resolve h; a domain or an h in the wrong unit?",
                              reach, "xyz"[a], reach / h_, h_, kMostRadii));
  }
}

void Simulation::set_clock(const Clock& clock) {
  step_ = clock.step;
  step_base_ = clock.step_base;
  time_base_ = clock.time_base;
}

namespace {
// Ids name rows of the timing table, thermo columns ("id.name") and files: letters, digits,
// '_' and '-' only, so that none of them breaks.
void check_id(const std::string& id, const char* kind) {
  auto allowed = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-'; };
  if (id.empty()) throw Error(fmt::format("a {} id must not be empty", kind));
  if (id.size() > 64 || !std::all_of(id.begin(), id.end(), allowed)) {
    std::string shown;  // a newline or a control character shown as \xNN, not printed
    for (unsigned char c : id.substr(0, 64))
      shown += std::isprint(c) ? std::string(1, static_cast<char>(c)) : fmt::format("\\x{:02x}", c);
    throw Error(fmt::format("{} id '{}'{}: use at most 64 letters, digits, '_' and '-'", kind, shown,
                            id.size() > 64 ? "..." : ""));
  }
}
}  // namespace

void Simulation::add_fix(std::unique_ptr<Fix> fix) {
  check_id(fix->id(), "fix");
  if (find_fix(fix->id()))
    throw Error(fmt::format("a fix with id '{}' exists already (unfix it first)", fix->id()));
  for (const char* job : fix->exclusive_jobs())
    for (const auto& f : fixes_)
      for (const char* other : f->exclusive_jobs())
        if (std::string(other) == job)
          throw Error(fmt::format("fix '{}' ({}): fix '{}' ({}) does the {} already, and a pipeline has one (pbf.unfix('{}') "
                                "first to replace it)",
                                fix->id(), fix->style(), f->id(), f->style(), job, f->id()));
  restore_saved_state(*fix);
  fixes_.push_back(std::move(fix));
  collect_boundaries();
}

void Simulation::set_saved_states(std::vector<SavedFixState> states, const std::string& source) {
  saved_states_ = std::move(states);
  saved_states_source_ = source;
  fixes_matched_.clear();
  check_saved_states_ = true;
  for (auto& f : fixes_) restore_saved_state(*f);  // fixes declared before the read
}

void Simulation::restore_saved_state(Fix& fix) {
  auto it = std::find_if(saved_states_.begin(), saved_states_.end(), [&](const auto& s) { return s.id == fix.id(); });
  if (it == saved_states_.end()) return;
  if (it->style != fix.style()) {
    spdlog::warn("fix '{}' is style '{}' here but '{}' in restart '{}': its saved state is not used", fix.id(),
                 fix.style(), it->style, saved_states_source_);
  } else {
    const std::string what = fmt::format("restart '{}', state of fix '{}' ({})", saved_states_source_, fix.id(),
                                         fix.style());
    ByteReader reader(it->bytes.data(), it->bytes.size(), what);
    fix.restore_state(reader);
    if (reader.left() != 0)
      throw Error(fmt::format("{}: {} bytes left over (written by another version of the style?)", what,
                              reader.left()));
  }
  fixes_matched_.push_back(fix.id());  // restored, or warned about once: not "afresh" too
  saved_states_.erase(it);
}

// At the first run after a restart: name fixes that are on one side only, since a pipeline
// that differs from the saved one does not continue the saved run exactly.
void Simulation::warn_unmatched_states() {
  if (!check_saved_states_) return;
  check_saved_states_ = false;
  for (const auto& s : saved_states_)
    spdlog::warn("fix '{}' ({}) is in restart '{}' but not in the pipeline: its saved state is dropped", s.id,
                 s.style, saved_states_source_);
  for (const auto& f : fixes_)
    if (f->in_restarts() && std::find(fixes_matched_.begin(), fixes_matched_.end(), f->id()) == fixes_matched_.end())
      spdlog::warn("fix '{}' ({}) is not in restart '{}': it starts afresh", f->id(), f->style(),
                   saved_states_source_);
  saved_states_.clear();
}

void Simulation::collect_boundaries() {
  boundaries_.clear();
  solids_.clear();
  for (const auto& f : fixes_) {
    if (DensityBoundary* b = f->density_boundary()) boundaries_.push_back(b);
    if (const SolidBody* s = f->solid_body()) solids_.push_back(s);
  }
  positions_changed();  // the density the cache holds may have changed
}

void Simulation::remove_fix(const std::string& id) {
  auto it = std::find_if(fixes_.begin(), fixes_.end(), [&](const auto& f) { return f->id() == id; });
  if (it == fixes_.end()) throw Error(fmt::format("no fix with id '{}'", id));
  fixes_.erase(it);
  collect_boundaries();
}

const Fix* Simulation::integrator() const {
  for (const auto& f : fixes_)
    if (f->integration() != Integration::none) return f.get();
  return nullptr;
}

bool Simulation::integrator_moves_positions() const {
  const Fix* f = integrator();
  return f && f->integration() == Integration::positions;
}

double Simulation::max_signal_speed() const {
  double c = 0;
  for (const auto& f : fixes_) c = std::max(c, f->signal_speed());
  return c;
}

double Simulation::max_kinematic_viscosity() const {
  double nu = 0;
  for (const auto& f : fixes_) nu = std::max(nu, f->kinematic_viscosity());
  return nu;
}

double Simulation::particle_mass() const {
  // Equal masses give their own value, whatever their count (their mean, a sum divided, can
  // be an ulp off in double precision, and would change when the count does).
  if (global_count() > 0) {
    const real common = uniform_mass(particles_.mass(), particles_.size(), particles_.distributed());
    return last_mean_mass_ = common > 0 ? double(common) : particles_.mean_mass();
  }
  for (const auto& f : fixes_)
    if (const double m = f->created_mass(*this); m > 0) return m;
  return last_mean_mass_;
}

Fix* Simulation::find_fix(const std::string& id) const {
  for (const auto& f : fixes_)
    if (f->id() == id) return f.get();
  return nullptr;
}

void Simulation::add_compute(std::unique_ptr<Compute> compute) {
  check_id(compute->id(), "compute");
  if (find_compute(compute->id()))
    throw Error(fmt::format("a compute with id '{}' exists already", compute->id()));
  if (domain_set_) compute->check_scene(*this);  // a point outside it named where the compute is defined
  computes_.push_back(std::move(compute));
}

void Simulation::remove_compute(const std::string& id) {
  auto it = std::find_if(computes_.begin(), computes_.end(), [&](const auto& c) { return c->id() == id; });
  if (it == computes_.end()) throw Error(fmt::format("no compute with id '{}'", id));
  computes_.erase(it);
}

Compute* Simulation::find_compute(const std::string& id) const {
  for (const auto& c : computes_)
    if (c->id() == id) return c.get();
  return nullptr;
}

const real* Simulation::solver_density() {
  if (const auto field = particles_.find("density")) return particles_.data(*field);
  refresh_neighbors();
  return summed_density().data();
}

const std::vector<real>& Simulation::summed_density() {
  refresh_density(false);
  return density_;
}

const std::vector<real>& Simulation::summed_volume() {
  refresh_density(true);
  return volume_;
}

// The density, and the volume when asked, in one pass over the particles (a pair sum, the
// walls' share, m / rho); the ghosts' come from their owners.
void Simulation::refresh_density(bool with_volume) {
  const bool density_current =
      density_version_ == positions_version_ && density_.size() == particles_.size_with_ghosts();
  const bool volume_current = volume_version_ == density_version_ && volume_.size() == density_.size();
  if (density_current && (volume_current || !with_volume)) return;
  const std::size_t n = particles_.size();
  if (density_current) {  // the volume only
    const real* m = particles_.mass();
    volume_.resize(density_.size());
    for_particles(density_.size(), [&](std::size_t i) { volume_[i] = m[i] / density_[i]; });
    volume_version_ = density_version_;
    return;
  }
  // (may rebuild the ghosts, which moves every array: pointers after it)
  if (grid_.particle_count() != particles_.size() || !lists_valid_) refresh_neighbors();
  const real* m = particles_.mass();
  density_.resize(particles_.size_with_ghosts());
  if (with_volume) volume_.resize(density_.size());
  update_ghost_positions();
  const real *x = particles_.x(), *y = particles_.y(), *z = particles_.z();
  // Within a run the boundaries' constants, and whether the masses are one, are those its
  // start found (each boundary's init, the run loop); between runs a script may have changed
  // the particles' masses or h.
  if (!running_)
    for (DensityBoundary* b : boundaries_) b->prepare(*this);
  const real common_mass = running_ ? run_uniform_mass_ : uniform_mass(m, n, particles_.distributed());
  const PairInput pairs{grid_, x, y, z, m, common_mass, kernels_, n};
  real* rho = density_.data();
  real* volume = with_volume ? volume_.data() : nullptr;
  for_blocks(n, [&](std::size_t begin, std::size_t end) {
    density_sums(pairs, begin, end, rho);
    for (std::size_t i = begin; i < end; ++i) {
      real grad[3] = {0, 0, 0};
      for (const DensityBoundary* b : boundaries_) b->add_density(*this, x[i], y[i], z[i], i, rho[i], grad);
      if (volume) volume[i] = m[i] / rho[i];
    }
  });
  update_ghosts({rho});
  if (volume)
    for (std::size_t i = n; i < density_.size(); ++i) volume[i] = m[i] / rho[i];
  density_version_ = positions_version_;
  if (volume) volume_version_ = density_version_;
}

real* Simulation::scratch(std::size_t k) {
  if (k >= kScratchArrays) throw Error(fmt::format("scratch array {} asked for; there are {}", k, kScratchArrays));
  scratch_[k].resize(particles_.size_with_ghosts());
  return scratch_[k].data();
}

void Simulation::swap_with_scratch(FieldId field, int component, std::size_t k) {
  scratch(k);  // checks k and sizes the array
  particles_.swap_values(field, component, scratch_[k]);
}

void Simulation::check_inside_domain() const {
  const auto& P = particles_;
  const std::size_t first =
      first_particle(P.size(), [&](std::size_t i) { return !domain_.contains(P.x()[i], P.y()[i], P.z()[i]); });
  if (first < P.size()) throw Error(outside_domain(first));
}

std::string Simulation::outside_domain(std::size_t i) const {
  const auto& P = particles_;
  return fmt::format("particle {} at ({}, {}, {}) is outside the domain [{}, {}] x [{}, {}] x [{}, {}]", P.ids()[i],
                     P.x()[i], P.y()[i], P.z()[i], domain_.lo[0], domain_.hi[0], domain_.lo[1], domain_.hi[1],
                     domain_.lo[2], domain_.hi[2]);
}

}  // namespace pbf
