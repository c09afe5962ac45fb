#include "engine/render/camera.hpp"

#include "engine/core/error.hpp"

namespace pbf::render {

namespace {
constexpr double kFieldOfViewY = 30.0 * 3.14159265358979323846 / 180.0;
constexpr double kFitMargin = 0.92;  // the bounding sphere spans 92% of the scene area's smaller side
}  // namespace

Camera::Camera(const ImageSpec& spec, const Domain& domain, int scene_width) {
  const Vec3 lo{domain.lo[0], domain.lo[1], domain.lo[2]}, hi{domain.hi[0], domain.hi[1], domain.hi[2]};
  const Vec3 mid = scaled({lo[0] + hi[0], lo[1] + hi[1], lo[2] + hi[2]}, 0.5);
  const double bounding_radius = std::max(0.5 * norm(sub(hi, lo)), 1e-12);
  const Vec3 target = spec.center.value_or(mid);
  forward = spec.eye ? sub(target, *spec.eye) : spec.direction;
  if (forward == Vec3{0, 0, 0} || !finite(forward)) throw Error("image: the camera position is the point it looks at");
  forward = unit(forward);
  if (norm(cross(forward, unit(spec.up))) <= 1e-3)
    throw Error("image: the camera looks along 'up'; choose another 'up' or camera position");
  right = cross(forward, spec.up);
  if (!finite(right)) right = cross(forward, unit(spec.up));  // an 'up' of 1e308 overflows
  right = unit(right);
  up = cross(right, forward);
  cx = 0.5 * scene_width;
  cy = 0.5 * spec.height;
  // At zoom 1 the sphere's outline, a circle of radius focal * tan(half-angle), fills
  // kFitMargin of the smaller side of the scene area.
  const double focal_zoom1 = 0.5 * spec.height / std::tan(0.5 * kFieldOfViewY);
  const double outline = 0.5 * kFitMargin * std::min(scene_width, spec.height);
  const double distance = bounding_radius / std::sin(std::atan(outline / focal_zoom1));
  eye = spec.eye ? *spec.eye : sub(target, scaled(forward, distance));
  focal = focal_zoom1 * spec.zoom;
  focus = norm(sub(target, eye));
  near = 1e-6 * focus;
}

}  // namespace pbf::render
