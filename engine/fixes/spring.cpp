// spring: the equations are at the top of spring.hpp.
#include "engine/fixes/spring.hpp"

#include <cmath>
#include <fmt/format.h>

#include "engine/core/error.hpp"
#include "engine/core/names.hpp"
#include "engine/core/simulation.hpp"
#include "engine/registry/builtin_styles.hpp"

namespace pbf {

namespace {

using Vec = std::array<double, 3>;

Vec vec(const Vec3& v) { return {v[0], v[1], v[2]}; }

}  // namespace

SpringFix::SpringFix(const std::string& id, const Params& p)
    : Fix(id, "spring"),
      body_name_(p.string("body")),
      other_name_(p.has("to_body") ? p.string("to_body") : ""),
      at_(vec(p.vec3("at"))),
      to_(vec(p.vec3("to"))),
      stiffness_(p.real("stiffness")),
      damping_(p.real("damping")),
      cable_(p.boolean("cable")) {
  const double placed = std::hypot(to_[0] - at_[0], to_[1] - at_[1], to_[2] - at_[2]);
  rest_length_ = p.has("length") ? p.real("length") : placed;
  if (other_name_ == body_name_) throw Error(fmt::format("parameter 'to_body': the spring's two ends are on '{}'", body_name_));
}

// The bodies by name, now that the pipeline is complete.
void SpringFix::init(Simulation& sim) {
  auto find = [&](const std::string& name, const char* param) {
    std::vector<std::string> bodies;
    for (const SolidBody* s : sim.solid_bodies())
      if (s->dynamics()) {
        bodies.push_back(s->name());
        if (s->name() == name) return s->dynamics();
      }
    throw Error(fmt::format("parameter '{}': no body '{}' in the pipeline (a solid with a density or a mass){}", param,
                            name, bodies.empty() ? std::string(" (it has none)") : did_you_mean(name, bodies)));
  };
  body_ = find(body_name_, "body");
  other_ = other_name_.empty() ? nullptr : find(other_name_, "to_body");
}

void SpringFix::ends(Vec& p, Vec& vp, Vec& q, Vec& vq) const {
  p = body_->transform().apply(at_);
  vp = body_->body().velocity_at(p);
  if (other_) {
    q = other_->transform().apply(to_);
    vq = other_->body().velocity_at(q);
  } else {
    q = to_;
    vq = {0, 0, 0};
  }
}

SpringFix::State SpringFix::state() const {
  State s;
  if (!body_) return s;
  Vec p, vp, q, vq;
  ends(p, vp, q, vq);
  const Vec d{q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  s.length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (s.length == 0) return s;  // the ends together: no direction to pull along
  const Vec u{d[0] / s.length, d[1] / s.length, d[2] / s.length};
  const double rate = (vq[0] - vp[0]) * u[0] + (vq[1] - vp[1]) * u[1] + (vq[2] - vp[2]) * u[2];
  s.tension = stiffness_ * (s.length - rest_length_) + damping_ * rate;
  if (cable_ && s.tension < 0) s.tension = 0;
  for (int a = 0; a < 3; ++a) s.force[a] = s.tension * u[a];
  return s;
}

void SpringFix::add_to(const SolidDynamics& body, Vec& force, Vec& torque) const {
  const bool mine = &body == body_, theirs = &body == other_;
  if (!mine && !theirs) return;
  Vec p, vp, q, vq;
  ends(p, vp, q, vq);
  const State s = state();
  const double sign = mine ? 1 : -1;
  const Vec at = mine ? p : q, c = body.body().position();
  const Vec F{sign * s.force[0], sign * s.force[1], sign * s.force[2]}, r{at[0] - c[0], at[1] - c[1], at[2] - c[2]};
  for (int a = 0; a < 3; ++a) force[a] += F[a];
  torque[0] += r[1] * F[2] - r[2] * F[1];
  torque[1] += r[2] * F[0] - r[0] * F[2];
  torque[2] += r[0] * F[1] - r[1] * F[0];
}

void register_spring(StyleRegistry& r) {
  r.add({"spring",
         StyleKind::fix,
         "a linear spring with damping from a point on a body to a fixed point or another body (a mooring)",
         {{"body", ParamType::String, std::nullopt, "", "the body (a solid with a density or a mass) it holds"},
          ParamSpec{"at", ParamType::Vector3, std::nullopt, "m", "where it holds the body, as the scene placed it"}
              .magnitude_at_most(1e6),
          ParamSpec{"to", ParamType::Vector3, std::nullopt, "m",
                    "its other end: a fixed point, or with to_body a point on that body as placed"}
              .magnitude_at_most(1e6),
          ParamSpec{"to_body", ParamType::String, std::nullopt, "", "a second body its other end holds", true},
          ParamSpec{"stiffness", ParamType::Real, std::nullopt, "N/m", "k: tension per metre of stretch"}.within(0, 1e12),
          ParamSpec{"length", ParamType::Real, std::nullopt, "m", "rest length (default: the ends' distance as placed)",
                    true}
              .within(0, 1e6),
          ParamSpec{"damping", ParamType::Real, 0.0, "N s/m", "c: tension per m/s of the ends' separating speed"}
              .within(0, 1e12),
          {"cable", ParamType::Bool, false, "", "pull only (a line that goes slack when shorter than its length)"}},
         [](const std::string& id, const Params& p) { return std::make_unique<SpringFix>(id, p); }, nullptr});
}

}  // namespace pbf
