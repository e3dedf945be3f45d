#include "gjkdem/dem/motion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gjkdem/math/real.hpp"

namespace gjkdem::dem {
namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

void check_motion(const PrescribedMotion& m) {
  if (!finite(m.center) || !finite(m.velocity) || !finite(m.angular_velocity) || !finite(m.amplitude))
    throw std::invalid_argument("a motion's vectors must be finite");
  if (!(std::isfinite(m.frequency) && m.frequency >= 0)) throw std::invalid_argument("the frequency must be >= 0 and finite");
  if (!std::isfinite(m.phase)) throw std::invalid_argument("the phase must be finite");
  if (m.table_times.size() != m.table_displacements.size())
    throw std::invalid_argument("the table needs one displacement per time");
  for (std::size_t k = 0; k < m.table_times.size(); ++k) {
    if (!std::isfinite(m.table_times[k]) || !finite(m.table_displacements[k]))
      throw std::invalid_argument("the table's times and displacements must be finite");
    if (k > 0 && !(m.table_times[k] > m.table_times[k - 1]))
      throw std::invalid_argument("the table's times must increase");
  }
}

MotionFrame motion_frame(const PrescribedMotion& m, Real t) noexcept {
  MotionFrame f;
  f.displacement = m.velocity * t;
  f.velocity = m.velocity;
  if (m.frequency > 0) {
    const Real w = 2 * kPi * m.frequency, arg = w * t + m.phase;
    f.displacement += m.amplitude * std::sin(arg);
    f.velocity += m.amplitude * (w * std::cos(arg));
  }
  const std::vector<Real>& times = m.table_times;
  if (!times.empty()) {
    const std::vector<Vec3>& d = m.table_displacements;
    if (t <= times.front()) {
      f.displacement += d.front();
    } else if (t >= times.back()) {
      f.displacement += d.back();
    } else {
      const std::size_t k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
      const Real span = times[k] - times[k - 1], s = (t - times[k - 1]) / span;
      f.displacement += d[k - 1] + (d[k] - d[k - 1]) * s;
      f.velocity += (d[k] - d[k - 1]) / span;
    }
  }
  const Real rate = length(m.angular_velocity);
  f.rotation = rate > 0 ? quat_from_axis_angle(m.angular_velocity / rate, rate * t) : Quat{};
  f.spin = m.angular_velocity;
  f.center = m.center + f.displacement;
  f.velocity_at_origin = f.velocity - cross(f.spin, f.center);
  return f;
}

}  // namespace gjkdem::dem
