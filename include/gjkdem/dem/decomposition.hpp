#pragma once
// Spatial decomposition of the bodies among ranks (MPI domains, issue 15):
// recursive coordinate bisection weighted by each body's cost. Each cut
// splits a box across its bodies' longest extent where the weight on each
// side is proportional to the parts that side gets, so the parts' costs
// stay balanced wherever the bodies gather (a hopper emptying into one
// corner). Ties in position are broken by id: the result depends on the
// bodies, not on the order they are listed in, and every rank computing it
// from the same data gets the same answer.
#include <cstdint>
#include <span>
#include <vector>

#include "gjkdem/math/vec3.hpp"

namespace gjkdem::dem {

/// A part's box of space: bodies whose centre lies in [lo, hi) belong to it.
/// Together the parts' boxes tile the domain given to bisect().
struct DomainBox {
  Vec3 lo, hi;
  bool holds(const Vec3& p) const noexcept {
    return p.x >= lo.x && p.x < hi.x && p.y >= lo.y && p.y < hi.y && p.z >= lo.z && p.z < hi.z;
  }
};

struct Decomposition {
  std::vector<DomainBox> boxes;      ///< one per part
  std::vector<std::uint32_t> owner;  ///< per body (input order), its part
};

/// Splits the bodies (centres, cost weights >= 0, distinct ids; spans of one
/// length) into `parts` >= 1 parts by recursive coordinate bisection of the
/// domain [lo, hi), which must hold every centre. A cut never separates
/// bodies at the same coordinate, so a part can get more than its share
/// (by at most the weight of the bodies on its cut's coordinate) or none.
Decomposition bisect(std::span<const Vec3> centres, std::span<const Real> weights,
                     std::span<const std::uint64_t> ids, int parts, const Vec3& lo, const Vec3& hi);

}  // namespace gjkdem::dem
