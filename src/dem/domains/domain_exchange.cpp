// Between the halves of a step: the inflows' new bodies, the boxes, the
// bodies that change domain and the ghosts (domains.hpp).
#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "domains/domain_records.hpp"
#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/dem/domains.hpp"
#include "gjkdem/dem/inflow.hpp"
#include "gjkdem/dem/periodic.hpp"
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

using namespace detail;

constexpr Real kInf = std::numeric_limits<Real>::infinity();

}  // namespace

std::uint64_t insert_inflow_bodies(World& w, StepContext& ctx, const DomainLayout& layout, DomainTransport& t) {
  DomainRole& role = *ctx.domain;
  constexpr std::uint64_t kNone = ~std::uint64_t{0};
  if (w.inflows.empty() || !inflows_due(w.inflows, w.inflow_states, {w.templates, w.materials}, w.time)) return kNone;  // the same answer on every rank
  std::vector<Body> near;   // this domain's bodies near an inflow
  std::vector<std::uint64_t> top{0};  // its highest id
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const Body& b = w.bodies[i];
    top[0] = std::max(top[0], b.id + 1);
    if (b.fixed || !role.owns(i)) continue;
    for (const Inflow& f : w.inflows)
      if (near_inflow(w.templates, f, b)) {
        near.push_back(b);
        break;
      }
  }
  Writer m;
  m.put(near), m.put(top);
  // Every rank places the bodies among all the bodies near the regions, as
  // a whole world does, from the same state: they agree without a word.
  std::vector<Body> all;
  for (std::size_t i = 0; i < w.bodies.size(); ++i)
    if (w.bodies[i].fixed) all.push_back(w.bodies[i]);
  std::vector<std::uint64_t> tops;
  for (const std::string& message : all_gather(t, m.take())) {
    Reader r(message);
    r.get(all), r.get(tops);
  }
  std::sort(all.begin(), all.end(), [](const Body& x, const Body& y) { return x.id < y.id; });
  const std::uint64_t first = *std::max_element(tops.begin(), tops.end());
  const std::size_t before = all.size();
  ctx.inserted = run_inflows(w.inflows, w.inflow_states, inflow_site(w), all, first);
  const std::vector<Body> fresh(all.begin() + static_cast<std::ptrdiff_t>(before), all.end());
  // All are kept: this domain's own, the others' as ghosts until the exchange.
  for (const Body& b : fresh) {
    w.bodies.push_back(b);
    role.foreign.push_back(layout.owner_of(b.position) == t.rank() ? 0 : 1);
  }
  return fresh.empty() ? kNone : first;
}

namespace {

// A fragment as it travels (its hull's vertices follow the records).
struct FragmentRecord {
  std::uint64_t parent = 0;
  std::uint32_t generation = 0;
  std::uint32_t surface = 0;
  std::uint64_t vertices = 0;
  Vec3 position;
  Quat orientation;
  Vec3 velocity;
  Vec3 angular_momentum;
};
static_assert(std::is_trivially_copyable_v<FragmentRecord>);

}  // namespace

DomainBreakage break_domain_grains(World& w, DomainRole& role, DomainTransport& t, bool found) {
  std::vector<FragmentRecord> records;
  std::vector<Vec3> vertices;
  if (found)
    for (const GrainSplit& s : find_splits(w, &role))
      for (const GrainSplit::Piece& p : s.fragments) {
        records.push_back({s.parent, s.generation, s.surface ? 1u : 0u, p.vertices.size(), p.position, p.orientation,
                           p.velocity, p.angular_momentum});
        vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
      }
  std::vector<std::uint64_t> top{w.bodies.empty() ? 0 : w.bodies.back().id + 1};
  Writer m;
  m.put(records), m.put(vertices), m.put(top);
  std::vector<GrainSplit> splits;
  std::uint64_t next_id = 0;
  for (const std::string& message : all_gather(t, m.take())) {
    Reader r(message);
    std::vector<FragmentRecord> in;
    std::vector<Vec3> points;
    std::vector<std::uint64_t> their_top;
    r.get(in), r.get(points), r.get(their_top);
    next_id = std::max(next_id, their_top.at(0));
    std::size_t at = 0;
    for (std::size_t k = 0; k + 1 < in.size(); k += 2) {
      GrainSplit s{.parent = in[k].parent, .generation = in[k].generation, .surface = in[k].surface != 0};
      for (std::size_t f = 0; f < 2; ++f) {
        const FragmentRecord& c = in[k + f];
        if (at + c.vertices > points.size()) throw std::runtime_error("a domain message is shorter than its contents");
        s.fragments[f] = {.vertices = std::vector<Vec3>(points.begin() + static_cast<std::ptrdiff_t>(at),
                                                        points.begin() + static_cast<std::ptrdiff_t>(at + c.vertices)),
                          .position = c.position, .orientation = c.orientation, .velocity = c.velocity,
                          .angular_momentum = c.angular_momentum};
        at += c.vertices;
        s.templates[f] = fragment_template(make_polytope(s.fragments[f].vertices), s.generation, s.surface);
      }
      splits.push_back(std::move(s));
    }
  }
  if (splits.empty()) return {};
  std::sort(splits.begin(), splits.end(), [](const GrainSplit& x, const GrainSplit& y) { return x.parent < y.parent; });
  const Real before = whole_contact_energy(w, t);
  apply_splits(w, splits, next_id, &role);
  return {static_cast<int>(splits.size()), before};
}

void sync_bonds(World& w, DomainRole& role, DomainTransport& t) {
  if (w.bonds.empty()) return;
  std::vector<BondBroken> mine;
  for (std::size_t k = 0; k < w.bonds.size(); ++k)
    if (!w.bonds[k].intact && role.bonds_told[k]) mine.push_back({k, w.bonds[k].broken_time});
  Writer m;
  m.put(mine);
  for (const std::string& message : all_gather(t, m.take())) {
    Reader r(message);
    std::vector<BondBroken> told;
    r.get(told);
    for (const BondBroken& b : told) {
      if (b.bond >= w.bonds.size()) throw std::runtime_error("a broken bond came damaged");
      w.bonds[b.bond].intact = 0;
      w.bonds[b.bond].broken_time = b.time;
      role.bonds_told[b.bond] = 0;
    }
  }
}

ExchangeCounts exchange_bodies(World& w, DomainRole& role, const DomainLayout& layout, DomainTransport& t) {
  const int me = t.rank(), ranks = t.size();
  ExchangeCounts counts;
  auto sent = [&](const std::vector<std::string>& out) {
    for (int r = 0; r < ranks; ++r)
      if (r != me) counts.bytes_sent += out[r].size();
  };
  StepWorkspace& work = w.work;
  const std::size_t n = w.bodies.size();
  const bool grew = w.search.boxes.boxes.size() != n;  // inflows inserted bodies: the broad phase lists them anew
  std::vector<std::uint8_t> ghost(n);  // other domains' moving bodies: replaced below, never boxed here
  for (std::size_t i = 0; i < n; ++i) ghost[i] = !role.owns(i) && !w.bodies[i].fixed;

  // Boxes are remade as update_boxes remakes them in a whole world, where
  // one body leaving its box has all those half way out remade too: the
  // domains agree whether any of their bodies left. A periodic world's
  // search cell is the whole world's: renewed, by all, when a box was
  // remade or a body wrapped anywhere, or a tilt was taken back.
  const int threads = detail::thread_count(w.settings.threads);
  const bool left =
      measure_box_motion(w.bodies, w.templates, w.settings.box_skin, w.search.boxes, threads, cell_drift(w.cell.now, w.search.cell), ghost);
  const std::vector<std::string> said = all_gather(t, std::string{left ? '1' : '0', w.search.renew_cell ? '1' : '0'});
  bool any_left = false, renew = false;
  for (const std::string& s : said) {
    if (s.size() != 2) throw std::runtime_error("a domain's box agreement came damaged");
    any_left |= s[0] == '1', renew |= s[1] == '1';
  }
  const std::size_t remade = remake_boxes(w.bodies, w.templates, w.settings.box_skin, w.search.boxes, threads,
                                          any_left ? kBoxBatchFraction : 1, ghost);
  w.search.renew_cell = false;
  if (any_left || renew) {
    w.search.cell = w.cell.now;  // before the ghosts' images below, and the search
    work.candidates_current = false;
  }

  // Bodies that left the region go to their owners, with their pairs.
  std::vector<std::vector<BodyRecord>> leaving(ranks);
  std::vector<std::pair<std::uint64_t, int>> moved;  // id, new owner (ids increasing)
  std::vector<std::uint8_t> gone(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Body& b = w.bodies[i];
    if (b.fixed || ghost[i]) continue;
    const int owner = layout.owner_of(b.position);
    if (owner == me) continue;
    leaving[owner].push_back(record_of(w, i));
    moved.emplace_back(b.id, owner);
    gone[i] = 1;
  }
  std::vector<std::vector<PairState>> leaving_pairs(ranks);
  auto new_owner = [&](std::uint64_t id) {
    const auto it = std::lower_bound(moved.begin(), moved.end(), std::pair<std::uint64_t, int>(id, -1));
    return it != moved.end() && it->first == id ? it->second : -1;
  };
  if (!moved.empty())
    for (const PairState& p : w.pairs) {
      const int lo = new_owner(p.key.lo), hi = new_owner(p.key.hi);
      if (lo >= 0) leaving_pairs[lo].push_back(p);
      if (hi >= 0 && hi != lo) leaving_pairs[hi].push_back(p);
    }
  std::vector<std::string> out(ranks);
  for (int r = 0; r < ranks; ++r) {
    Writer m;
    m.put(leaving[r]), m.put(leaving_pairs[r]);
    out[r] = m.take();
  }
  counts.moved_out = moved.size();
  sent(out);
  std::vector<BodyRecord> arrived;
  std::vector<PairState> arrived_pairs;
  for (const std::string& message : t.exchange(std::move(out))) {
    Reader m(message);
    m.get(arrived), m.get(arrived_pairs);
  }
  if (!arrived_pairs.empty()) {
    w.pairs.insert(w.pairs.end(), arrived_pairs.begin(), arrived_pairs.end());
    sort_unique(w.pairs, [](const PairState& p) { return p.key; });
  }

  // The ghosts: each owned body goes to the domains its box reaches into
  // (the box holding the boxes of their owned bodies).
  auto staying = [&](std::size_t i) { return !w.bodies[i].fixed && !ghost[i] && !gone[i]; };
  Aabb reach{{kInf, kInf, kInf}, {-kInf, -kInf, -kInf}};
  auto grow = [&](const Aabb& box) { reach.lo = min(reach.lo, box.lo), reach.hi = max(reach.hi, box.hi); };
  for (std::size_t i = 0; i < n; ++i)
    if (staying(i)) grow(w.search.boxes.boxes[i]);
  for (const BodyRecord& r : arrived) grow(r.box);
  std::string reach_bytes(sizeof reach, '\0');
  std::memcpy(reach_bytes.data(), &reach, sizeof reach);
  std::vector<Aabb> reaches(ranks);
  const std::vector<std::string> all_reaches = all_gather(t, reach_bytes);
  for (int r = 0; r < ranks; ++r) {
    if (all_reaches[r].size() != sizeof(Aabb)) throw std::runtime_error("a domain's reach came damaged");
    std::memcpy(&reaches[r], all_reaches[r].data(), sizeof(Aabb));
  }
  // In a periodic cell, a box reaches a domain through any of its images
  // in the search cell (the domain's broad phase then finds the image itself).
  const std::vector<Vec3> shifts = w.cell.now.active() ? image_shifts(w.search.cell) : std::vector<Vec3>{Vec3{}};
  std::vector<std::vector<BodyRecord>> ghosts(ranks);
  auto send_ghost = [&](const Aabb& box, const auto& record) {  // record() made only for a domain it reaches
    for (int r = 0; r < ranks; ++r) {
      if (r == me) continue;
      for (const Vec3& s : shifts)
        if (overlaps(Aabb{box.lo + s, box.hi + s}, reaches[r])) {
          ghosts[r].push_back(record());
          break;
        }
    }
  };
  // A body held by an intact bond also goes where its partner is owned:
  // its box grown by twice the largest reach holds the partner's centre
  // (the two touch at their face), so every domain computes the bonds of
  // the bodies it owns (bonds.hpp).
  const std::vector<std::uint64_t> held = held_bodies(w.bonds);
  const Real grow_by = 2 * role.whole_reach;
  auto ghost_box = [&](const Aabb& box, std::uint64_t id) {
    if (!std::binary_search(held.begin(), held.end(), id)) return box;
    return Aabb{box.lo - Vec3{grow_by, grow_by, grow_by}, box.hi + Vec3{grow_by, grow_by, grow_by}};
  };
  for (std::size_t i = 0; i < n; ++i)
    if (staying(i)) send_ghost(ghost_box(w.search.boxes.boxes[i], w.bodies[i].id), [&] { return record_of(w, i); });
  for (const BodyRecord& r : arrived) send_ghost(ghost_box(r.box, r.body.id), [&] { return r; });
  out.assign(ranks, {});
  for (int r = 0; r < ranks; ++r) {
    Writer m;
    m.put(ghosts[r]);
    out[r] = m.take();
  }
  sent(out);
  counts.bytes_sent += (ranks - 1) * (sizeof reach + 2);  // the reaches and the box agreement
  std::vector<BodyRecord> seen;
  for (const std::string& message : t.exchange(std::move(out))) Reader(message).get(seen);
  std::sort(seen.begin(), seen.end(), [](const BodyRecord& x, const BodyRecord& y) { return x.body.id < y.body.id; });
  counts.ghosts = seen.size();

  // The same bodies as before (the common case in a bed at rest): the
  // ghosts are refreshed where they lie.
  std::size_t k = 0;
  bool same = moved.empty() && arrived.empty();
  for (std::size_t i = 0; same && i < n; ++i)
    if (ghost[i]) same = k < seen.size() && seen[k++].body.id == w.bodies[i].id;
  if (same && k == seen.size()) {
    bool boxes_changed = remade > 0;
    k = 0;
    BoxCache& c = w.search.boxes;
    for (std::size_t i = 0; i < n; ++i) {
      if (!ghost[i]) {
        counts.owned += w.bodies[i].fixed ? 0 : 1;
        continue;
      }
      const BodyRecord& r = seen[k++];
      boxes_changed = boxes_changed || !same_bits(&r.anchor_position, &c.anchor_position[i], sizeof(Vec3)) ||
                      !same_bits(&r.anchor_orientation, &c.anchor_orientation[i], sizeof(Quat));
      w.bodies[i] = r.body;
      c.boxes[i] = r.box, c.anchor_position[i] = r.anchor_position, c.anchor_orientation[i] = r.anchor_orientation;
    }
    if (boxes_changed) work.candidates_current = false;
    if (grew) work.static_ready = work.candidates_current = false;
    return counts;
  }

  // Else the domain is made again: fixed, staying, arrived and seen bodies.
  std::vector<BodyRecord> records;
  std::vector<std::uint8_t> foreign;
  records.reserve(n + arrived.size() + seen.size());
  for (std::size_t i = 0; i < n; ++i)
    if (w.bodies[i].fixed || staying(i)) records.push_back(record_of(w, i)), foreign.push_back(w.bodies[i].fixed ? 1 : 0);
  for (const BodyRecord& r : arrived) records.push_back(r), foreign.push_back(0);
  for (const std::uint8_t f : foreign) counts.owned += f ? 0 : 1;
  for (const BodyRecord& r : seen) records.push_back(r), foreign.push_back(1);
  set_bodies(w, role, records, foreign);
  work.static_ready = false;  // the bodies' indices changed
  work.candidates_current = false;
  return counts;
}

}  // namespace gjkdem::dem
