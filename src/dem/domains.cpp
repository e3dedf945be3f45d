// Domains of a world: cutting, exchanging bodies between steps, gathering
// the whole on rank 0 (domains.hpp). Messages are arrays of plain records
// copied as bytes: every rank runs the same build.
#include "gjkdem/dem/domains.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "gjkdem/dem/boxes.hpp"
#include "parallel.hpp"

namespace gjkdem::dem {
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

// A body as it travels: its state and its box with the box's anchors.
struct BodyRecord {
  Body body;
  Aabb box;
  Vec3 anchor_position;
  Quat anchor_orientation;
};

// A touching contact as it travels to rank 0: bodies by id (a plane by its index).
struct ContactRecord {
  PairKey key;
  std::uint64_t a = 0, b = 0;
  StepContact contact;
};

static_assert(std::is_trivially_copyable_v<BodyRecord> && std::is_trivially_copyable_v<PairState> &&
              std::is_trivially_copyable_v<ContactRecord>);

// A message: arrays of records, each preceded by its count.
class Writer {
 public:
  template <class T>
  void put(const std::vector<T>& items) {
    const std::uint64_t n = items.size();
    bytes_.append(reinterpret_cast<const char*>(&n), sizeof n);
    bytes_.append(reinterpret_cast<const char*>(items.data()), n * sizeof(T));
  }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

class Reader {
 public:
  explicit Reader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  void get(std::vector<T>& items) {  // appends
    std::uint64_t n = 0;
    take(&n, sizeof n);
    const std::size_t old = items.size();
    items.resize(old + n);
    take(items.data() + old, n * sizeof(T));
  }

 private:
  void take(void* to, std::size_t n) {
    if (n > bytes_.size() - at_) throw std::runtime_error("a domain message is shorter than its contents");
    std::memcpy(to, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

BodyRecord record_of(const World& w, std::size_t i) {
  const BoxCache& c = w.work.boxes;
  return {w.bodies[i], c.boxes[i], c.anchor_position[i], c.anchor_orientation[i]};
}

bool owned(const World& w, std::size_t i) { return w.work.foreign.empty() || !w.work.foreign[i]; }

// The index of the body with this id (bodies in increasing id order).
std::uint32_t index_of_id(std::span<const Body> bodies, std::uint64_t id) {
  const auto it =
      std::lower_bound(bodies.begin(), bodies.end(), id, [](const Body& b, std::uint64_t v) { return b.id < v; });
  return static_cast<std::uint32_t>(it - bodies.begin());
}

// A contact's share of the driven pieces' power (step.cpp's sum), on its way to rank 0.
struct PowerTerm {
  PairKey key;
  Real on_a = 0, on_b = 0;  // driven_power of a's motion, of b's
  std::uint8_t driven = 0;  // 1: a is driven, 2: b is
};

// Replaces the domain's bodies and boxes by `records` (any order).
void set_bodies(World& w, std::vector<BodyRecord>& records, std::span<const std::uint8_t> foreign_of_record) {
  std::vector<std::uint64_t> driven_ids;  // driven bodies are fixed: every domain holds them
  for (const DrivenBody& d : w.driven) driven_ids.push_back(w.bodies[d.body].id);
  std::vector<std::uint32_t> order(records.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t p, std::uint32_t q) { return records[p].body.id < records[q].body.id; });
  const std::size_t n = records.size();
  BoxCache& c = w.work.boxes;
  w.bodies.resize(n);
  c.boxes.resize(n), c.anchor_position.resize(n), c.anchor_orientation.resize(n), c.moved.resize(n);
  w.work.foreign.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyRecord& r = records[order[i]];
    w.bodies[i] = r.body;
    c.boxes[i] = r.box, c.anchor_position[i] = r.anchor_position, c.anchor_orientation[i] = r.anchor_orientation;
    w.work.foreign[i] = foreign_of_record[order[i]];
  }
  for (std::size_t k = 0; k < w.driven.size(); ++k) w.driven[k].body = index_of_id(w.bodies, driven_ids[k]);
}

// Sorts records by key, keeping the first of equal keys (the copies of a
// pair or contact two domains share are equal). Sorts indices: the records
// are large.
template <class T, class Key>
void sort_unique(std::vector<T>& items, Key key) {
  std::vector<std::uint32_t> order(items.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t p, std::uint32_t q) { return key(items[p]) < key(items[q]); });
  std::vector<T> out;
  out.reserve(items.size());
  for (const std::uint32_t k : order)
    if (out.empty() || !(key(out.back()) == key(items[k]))) out.push_back(items[k]);
  items = std::move(out);
}

bool same_bits(const void* a, const void* b, std::size_t n) { return std::memcmp(a, b, n) == 0; }

}  // namespace

std::vector<std::string> all_gather(DomainTransport& t, const std::string& mine) {
  return t.exchange(std::vector<std::string>(static_cast<std::size_t>(t.size()), mine));
}

int DomainLayout::owner_of(const Vec3& centre) const noexcept {
  for (std::size_t r = 0; r < regions.size(); ++r)
    if (regions[r].holds(centre)) return static_cast<int>(r);
  return 0;  // not finite: the run's guards fail it at the next output
}

DomainLayout layout_domains(const World& w, int ranks, std::span<const Real> weights) {
  std::vector<Vec3> centres;
  std::vector<Real> costs;
  std::vector<std::uint64_t> ids;
  Vec3 lo{kInf, kInf, kInf}, hi = -lo;
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const Body& b = w.bodies[i];
    if (b.fixed) continue;
    centres.push_back(b.position);
    costs.push_back(weights.empty() ? 1 : weights[i]);
    ids.push_back(b.id);
    lo = min(lo, b.position), hi = max(hi, b.position);
  }
  if (centres.empty()) lo = hi = {};
  // bisect's domain is half-open: nudge its top above the highest centre.
  for (int a = 0; a < 3; ++a) hi[a] = std::nextafter(hi[a] + std::fabs(hi[a]) * 1e-12, kInf);
  Decomposition d = bisect(centres, costs, ids, ranks, lo, hi);
  for (DomainBox& box : d.boxes)  // the outer faces to infinity
    for (int a = 0; a < 3; ++a) {
      if (box.lo[a] == lo[a]) box.lo[a] = -kInf;
      if (box.hi[a] == hi[a]) box.hi[a] = kInf;
    }
  return {std::move(d.boxes)};
}

std::string domains_unsupported(const World& w) {
  if (w.cell.active()) return "periodic boundaries";
  return "";
}

World make_domain(const World& whole, const DomainLayout& layout, int rank) {
  World d;
  d.settings = whole.settings;
  d.templates = whole.templates;
  d.materials = whole.materials;
  d.material_pairs = whole.material_pairs;
  d.planes = whole.planes;
  d.motions = whole.motions;
  d.inflows = whole.inflows;
  d.inflow_states = whole.inflow_states;
  d.work.inflows_by_domains = true;
  d.time = whole.time;
  d.forces_current = whole.forces_current;
  d.wall_work = whole.wall_work;
  d.stats = whole.stats;
  const BoxCache& boxes = whole.work.boxes;
  const bool boxed = boxes.anchor_position.size() == whole.bodies.size() && boxes.boxes.size() == whole.bodies.size();
  std::vector<std::uint64_t> mine;
  for (std::size_t i = 0; i < whole.bodies.size(); ++i) {
    const Body& b = whole.bodies[i];
    const bool own = !b.fixed && layout.owner_of(b.position) == rank;
    if (!b.fixed && !own) continue;
    d.bodies.push_back(b);
    d.work.foreign.push_back(own ? 0 : 1);
    if (own) mine.push_back(b.id);
    if (boxed) {
      d.work.boxes.boxes.push_back(boxes.boxes[i]);
      d.work.boxes.anchor_position.push_back(boxes.anchor_position[i]);
      d.work.boxes.anchor_orientation.push_back(boxes.anchor_orientation[i]);
    }
  }
  d.work.boxes.moved.resize(d.work.boxes.boxes.size());
  for (DrivenBody driven : whole.driven) {
    driven.body = index_of_id(d.bodies, whole.bodies[driven.body].id);
    d.driven.push_back(driven);
  }
  for (const PairState& p : whole.pairs)
    if (std::binary_search(mine.begin(), mine.end(), p.key.lo) || std::binary_search(mine.begin(), mine.end(), p.key.hi))
      d.pairs.push_back(p);
  return d;
}

std::vector<Real> body_costs(const World& w) {
  std::vector<Real> cost(w.bodies.size(), 1);
  std::vector<std::uint64_t> ids(w.bodies.size());
  for (std::size_t i = 0; i < ids.size(); ++i) ids[i] = w.bodies[i].id;
  auto count = [&](std::uint64_t id) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    if (it != ids.end() && *it == id) cost[static_cast<std::size_t>(it - ids.begin())] += 1;
  };
  for (const PairState& p : w.pairs) count(p.key.lo), count(p.key.hi);
  return cost;
}

std::uint64_t insert_inflow_bodies(World& w, const DomainLayout& layout, DomainTransport& t) {
  constexpr std::uint64_t kNone = ~std::uint64_t{0};
  if (w.inflows.empty() || !inflows_due(w)) return kNone;  // the same answer on every rank
  std::vector<Body> near;   // this domain's bodies near an inflow
  std::vector<std::uint64_t> top{0};  // its highest id
  for (std::size_t i = 0; i < w.bodies.size(); ++i) {
    const Body& b = w.bodies[i];
    top[0] = std::max(top[0], b.id + 1);
    if (b.fixed || !owned(w, i)) continue;
    for (const Inflow& f : w.inflows)
      if (near_inflow(w, f, b)) {
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
  std::swap(w.bodies, all);
  const std::size_t before = w.bodies.size();
  w.work.inserted = run_inflows(w, first);
  std::vector<Body> fresh(w.bodies.begin() + static_cast<std::ptrdiff_t>(before), w.bodies.end());
  std::swap(w.bodies, all);
  // All are kept: this domain's own, the others' as ghosts until the exchange.
  for (const Body& b : fresh) {
    w.bodies.push_back(b);
    w.work.foreign.push_back(layout.owner_of(b.position) == t.rank() ? 0 : 1);
  }
  return fresh.empty() ? kNone : first;
}

ExchangeCounts exchange_bodies(World& w, const DomainLayout& layout, DomainTransport& t) {
  const int me = t.rank(), ranks = t.size();
  ExchangeCounts counts;
  auto sent = [&](const std::vector<std::string>& out) {
    for (int r = 0; r < ranks; ++r)
      if (r != me) counts.bytes_sent += out[r].size();
  };
  StepWorkspace& work = w.work;
  const std::size_t n = w.bodies.size();
  const bool grew = work.boxes.boxes.size() != n;  // inflows inserted bodies: the broad phase lists them anew
  std::vector<std::uint8_t> ghost(n);  // other domains' moving bodies: replaced below, never boxed here
  for (std::size_t i = 0; i < n; ++i) ghost[i] = !owned(w, i) && !w.bodies[i].fixed;

  // Boxes are remade as update_boxes remakes them in a whole world, where
  // one body leaving its box has all those half way out remade too: the
  // domains agree whether any of their bodies left.
  const int threads = detail::thread_count(w.settings.threads);
  const bool left = measure_box_motion(w.bodies, w.templates, w.settings.box_skin, work.boxes, threads, 0, ghost);
  const std::vector<std::string> said = all_gather(t, left ? "1" : "");
  const bool any_left = std::any_of(said.begin(), said.end(), [](const std::string& s) { return !s.empty(); });
  const std::size_t remade = remake_boxes(w.bodies, w.templates, w.settings.box_skin, work.boxes, threads,
                                          any_left ? kBoxBatchFraction : 1, ghost);

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
    if (staying(i)) grow(work.boxes.boxes[i]);
  for (const BodyRecord& r : arrived) grow(r.box);
  std::string reach_bytes(sizeof reach, '\0');
  std::memcpy(reach_bytes.data(), &reach, sizeof reach);
  std::vector<Aabb> reaches(ranks);
  const std::vector<std::string> all_reaches = all_gather(t, reach_bytes);
  for (int r = 0; r < ranks; ++r) {
    if (all_reaches[r].size() != sizeof(Aabb)) throw std::runtime_error("a domain's reach came damaged");
    std::memcpy(&reaches[r], all_reaches[r].data(), sizeof(Aabb));
  }
  std::vector<std::vector<BodyRecord>> ghosts(ranks);
  auto send_ghost = [&](const BodyRecord& record) {
    for (int r = 0; r < ranks; ++r)
      if (r != me && overlaps(record.box, reaches[r])) ghosts[r].push_back(record);
  };
  for (std::size_t i = 0; i < n; ++i)
    if (staying(i)) send_ghost(record_of(w, i));
  for (const BodyRecord& r : arrived) send_ghost(r);
  out.assign(ranks, {});
  for (int r = 0; r < ranks; ++r) {
    Writer m;
    m.put(ghosts[r]);
    out[r] = m.take();
  }
  sent(out);
  counts.bytes_sent += (ranks - 1) * (sizeof reach + 1);  // the reaches and the box agreement
  std::vector<BodyRecord> seen;
  for (const std::string& message : t.exchange(std::move(out))) Reader(message).get(seen);
  std::sort(seen.begin(), seen.end(), [](const BodyRecord& x, const BodyRecord& y) { return x.body.id < y.body.id; });
  counts.ghosts = seen.size();
  work.kicked_bodies = n;  // every body took its first half kick where it was owned

  // The same bodies as before (the common case in a bed at rest): the
  // ghosts are refreshed where they lie.
  std::size_t k = 0;
  bool same = moved.empty() && arrived.empty();
  for (std::size_t i = 0; same && i < n; ++i)
    if (ghost[i]) same = k < seen.size() && seen[k++].body.id == w.bodies[i].id;
  if (same && k == seen.size()) {
    bool boxes_changed = remade > 0;
    k = 0;
    BoxCache& c = work.boxes;
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
  set_bodies(w, records, foreign);
  work.kicked_bodies = w.bodies.size();
  work.static_ready = false;  // the bodies' indices changed
  work.candidates_current = false;
  return counts;
}

void gather_world(const World& d, DomainTransport& t, World& whole) {
  std::vector<BodyRecord> bodies;
  std::vector<ContactRecord> contacts;
  for (std::size_t i = 0; i < d.bodies.size(); ++i)
    if (owned(d, i) || (t.rank() == 0 && d.bodies[i].fixed)) bodies.push_back(record_of(d, i));
  for (std::size_t k = 0; k < d.work.contacts.size(); ++k) {
    const StepContact& c = d.work.contacts[k];
    if (!c.active) continue;
    ContactRecord r{d.work.keys[k], c.a_is_plane ? c.a : d.bodies[c.a].id, d.bodies[c.b].id, c};
    contacts.push_back(r);
  }
  std::vector<PairState> pairs;  // with an owned body (a domain lists no other)
  pairs.reserve(d.pairs.size());
  pairs.insert(pairs.end(), d.pairs.begin(), d.pairs.end());
  Writer m;
  m.put(bodies), m.put(pairs), m.put(contacts);
  std::vector<std::string> out(t.size());
  out[0] = m.take();
  const std::vector<std::string> in = t.exchange(std::move(out));
  if (t.rank() != 0) return;
  bodies.clear(), pairs.clear(), contacts.clear();
  for (const std::string& message : in) {
    Reader r(message);
    r.get(bodies), r.get(pairs), r.get(contacts);
  }
  std::sort(bodies.begin(), bodies.end(), [](const BodyRecord& x, const BodyRecord& y) { return x.body.id < y.body.id; });
  sort_unique(pairs, [](const PairState& p) { return p.key; });
  sort_unique(contacts, [](const ContactRecord& c) { return c.key; });
  const std::size_t n = bodies.size();
  whole.bodies.resize(n);
  BoxCache& boxes = whole.work.boxes;
  boxes.boxes.resize(n), boxes.anchor_position.resize(n), boxes.anchor_orientation.resize(n), boxes.moved.resize(n);
  std::vector<std::uint64_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyRecord& r = bodies[i];
    whole.bodies[i] = r.body;
    boxes.boxes[i] = r.box, boxes.anchor_position[i] = r.anchor_position, boxes.anchor_orientation[i] = r.anchor_orientation;
    ids[i] = r.body.id;
  }
  auto index_of = [&](std::uint64_t id) {
    return static_cast<std::uint32_t>(std::lower_bound(ids.begin(), ids.end(), id) - ids.begin());
  };
  whole.pairs = std::move(pairs);
  whole.inflow_states = d.inflow_states;  // the same on every rank
  whole.planes = d.planes;  // where their motions have them
  whole.work.motion_frames = d.work.motion_frames;
  whole.time = d.time;
  whole.forces_current = d.forces_current;
  whole.wall_work = d.wall_work;
  // The stats and the fixed bodies' reactions, summed as step.cpp sums
  // them: in the order of the contact list, which is the order of keys.
  StepStats stats;
  whole.work.contacts.clear(), whole.work.keys.clear();
  for (Body& b : whole.bodies)
    if (b.fixed) b.force = b.torque = {};
  for (ContactRecord& r : contacts) {
    StepContact& c = r.contact;
    c.a = c.a_is_plane ? static_cast<std::uint32_t>(r.a) : index_of(r.a);
    c.b = index_of(r.b);
    Body& b = whole.bodies[c.b];
    if (b.fixed) {
      b.force += c.force;
      b.torque += c.torque - cross(b.position, c.force);
    }
    if (!c.a_is_plane && whole.bodies[c.a].fixed) {
      Body& a = whole.bodies[c.a];
      a.force -= c.force;
      a.torque -= c.torque - cross(a.position, c.force);
    }
    stats.elastic_energy += c.elastic;
    ++stats.contacts;
    if (c.a_is_plane || whole.bodies[c.a].fixed || b.fixed) ++stats.wall_contacts;
    whole.work.contacts.push_back(c);
    whole.work.keys.push_back(r.key);
  }
  stats.wall_power = d.stats.wall_power;  // rank 0's is the whole world's (whole_wall_power)
  whole.stats = stats;
  whole.work.candidates_current = false;
}

Real whole_wall_power(const World& d, DomainTransport& t) {
  std::vector<PowerTerm> terms;
  for (std::size_t k = 0; k < d.work.contacts.size(); ++k) {
    const StepContact& c = d.work.contacts[k];
    if (!c.active) continue;
    const std::uint32_t motion_a = c.a_is_plane ? d.planes[c.a].motion : d.bodies[c.a].motion;
    const std::uint32_t motion_b = d.bodies[c.b].motion;
    if (!motion_a && !motion_b) continue;
    PowerTerm p{d.work.keys[k]};
    if (motion_a) p.on_a = driven_power(d.work.motion_frames[motion_a - 1], c.force, c.torque), p.driven |= 1;
    if (motion_b) p.on_b = driven_power(d.work.motion_frames[motion_b - 1], c.force, c.torque), p.driven |= 2;
    terms.push_back(p);
  }
  Writer m;
  m.put(terms);
  std::vector<std::string> out(t.size());
  out[0] = m.take();
  const std::vector<std::string> in = t.exchange(std::move(out));
  if (t.rank() != 0) return 0;
  terms.clear();
  for (const std::string& message : in) Reader(message).get(terms);
  sort_unique(terms, [](const PowerTerm& p) { return p.key; });
  Real power = 0;  // as step.cpp sums it: contact by contact, a's share then b's
  for (const PowerTerm& p : terms) {
    if (p.driven & 1) power += p.on_a;
    if (p.driven & 2) power -= p.on_b;
  }
  return power;
}

}  // namespace gjkdem::dem
