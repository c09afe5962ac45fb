#include "engine/geometry/wall_contact.hpp"

#include <algorithm>
#include <cmath>

namespace pbf {

Contact keep_out(const SolidMap& map, const ContactDistances& at, const real p0[3], real start_distance, real p[3]) {
  real d, g[3];
  const real step[3] = {p[0] - p0[0], p[1] - p0[1], p[2] - p0[2]};
  const real len = std::sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]);
  const real hair = at.hair, gap = at.gap, reach = gap - hair / 2;
  // A non-finite move (a blow-up, which the run loop names at the end of the step) has no
  // path to march along: the march below would never end.
  if (!std::isfinite(len)) return Contact::none;
  if (far_from_wall(start_distance, len, reach)) return Contact::none;
  const auto where = map.distance(p[0], p[1], p[2], d, nullptr);
  const bool inside = where == SolidMap::Where::wall || (where == SolidMap::Where::near && d < reach);
  if (!inside && len < start_distance - reach) return Contact::none;  // cannot have reached the wall
  // March from the start: the first point at or behind the surface is where it met the wall.
  const real min_step = at.min_step;
  real s = 0, hit[3], dh = 0, gh[3];
  bool met = false;
  while (true) {
    for (int a = 0; a < 3; ++a) hit[a] = p0[a] + (len > 0 ? s / len : 0) * step[a];
    const auto w = map.distance(hit[0], hit[1], hit[2], dh, gh);
    if (w == SolidMap::Where::wall) return Contact::lost;
    if (w == SolidMap::Where::near && dh < reach) {
      met = true;
      break;
    }
    if (s >= len) break;
    s = std::min(len, s + std::max(w == SolidMap::Where::fluid ? real(map.far_distance()) : dh, min_step));
  }
  if (!met) return Contact::none;  // passed near the wall without touching it
  // Take away the motion into the wall at the contact point, keep the motion along it.
  const real gl = std::sqrt(gh[0] * gh[0] + gh[1] * gh[1] + gh[2] * gh[2]);
  if (gl > 0) {
    // p's distance in front of the tangent plane at the contact
    const real into = ((p[0] - hit[0]) * gh[0] + (p[1] - hit[1]) * gh[1] + (p[2] - hit[2]) * gh[2]) / gl + dh;
    if (into < gap)
      for (int a = 0; a < 3; ++a) p[a] -= (into - gap) * gh[a] / gl;
  }
  // To the gap in front of the surface: steps of the missing distance along the distance's
  // gradient (one for a flat wall). Not Newton steps, d / |grad d|: in a cell at an edge or a
  // corner the interpolated distance is flat in places, and a small gradient would throw the
  // particle across the domain.
  for (int it = 0; it < 4; ++it) {
    const auto w = map.distance(p[0], p[1], p[2], d, g);
    if (w == SolidMap::Where::wall) return Contact::lost;
    if (w == SolidMap::Where::fluid || d >= reach) break;
    const real gl = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    if (gl == 0) break;
    for (int a = 0; a < 3; ++a) p[a] -= (d - gap) * g[a] / gl;
  }
  return Contact::moved;
}

}  // namespace pbf
