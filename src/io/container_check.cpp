#include "container_check.hpp"

#include <cmath>

namespace gjkdem::io::detail {

std::vector<std::string> bodies_outside_containers(std::vector<ContainerWall>& walls, const std::string& who,
                                                   std::span<const Vec3> positions) {
  std::vector<std::string> warnings;
  for (ContainerWall& m : walls) {
    const double work = static_cast<double>(m.mesh.triangles.size()) * static_cast<double>(positions.size());
    if (work > kMaxContainmentWork) continue;
    if (!m.closed) m.closed = is_watertight(m.mesh);  // once per wall, and only for scenes with generators
    if (!*m.closed) continue;
    std::size_t inside = 0;
    for (const Vec3& p : positions)
      if (overlaps(m.box, {p, p}) && std::fabs(winding_number(m.mesh, p)) > 0.5) ++inside;
    if (inside > 0 && inside < positions.size())
      warnings.push_back(who + ": " + std::to_string(positions.size() - inside) + " of its " +
                         std::to_string(positions.size()) + " bodies lie outside the closed mesh " + m.label +
                         " that holds the others, and will fall away from it: keep the region inside");
  }
  return warnings;
}

}  // namespace gjkdem::io::detail
