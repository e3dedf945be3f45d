// Domains of a world: their regions, cutting a domain from the whole world,
// and gathering the whole on rank 0 (domains.hpp).
#include "gjkdem/dem/domains.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>

#include "contacts/contact_sums.hpp"
#include "domains/domain_records.hpp"
#include "gjkdem/tolerances.hpp"

namespace gjkdem::dem {
namespace {

using namespace detail;

constexpr Real kInf = std::numeric_limits<Real>::infinity();

// A touching contact as it travels to rank 0: bodies by id (a plane by its index).
struct ContactRecord {
  PairKey key;
  std::uint64_t a = 0, b = 0;
  StepContact contact;
};

static_assert(std::is_trivially_copyable_v<ContactRecord>);

// Every rank's records, gathered on rank 0 and sorted by key (copies of a
// contact two domains share kept once); empty on the others.
template <class T, class Key>
std::vector<T> gather_sorted(DomainTransport& t, std::vector<T> mine, Key key) {
  Writer m;
  m.put(mine);
  const std::vector<std::string> in = gather_to_root(t, m.take());
  mine.clear();
  if (t.rank() != 0) return mine;
  for (const std::string& message : in) Reader(message).get(mine);
  sort_unique(mine, key);
  return mine;
}

// Every rank's shares of the force evaluation's sums (contacts/
// contact_sums.hpp) that `wanted` keeps, added on rank 0 in key order, as
// one rank adds its list (zero sums on the other ranks).
template <class Wanted>
ContactSums gathered_sums(const World& d, DomainTransport& t, Wanted wanted) {
  std::vector<ContactTerm> terms;
  for (std::size_t k = 0; k < d.results.contacts.size(); ++k) {
    const StepContact& c = d.results.contacts[k];
    if (!c.active) continue;
    ContactTerm term =
        contact_term(c, image_shift_of(d.cell.now, c), d.bodies, d.planes, d.results.motion_frames, d.cell.now, d.cell.rate);
    term.key = d.results.keys[k];
    if (wanted(term)) terms.push_back(term);
  }
  ContactSums sums;
  for (const ContactTerm& term : gather_sorted(t, std::move(terms), [](const ContactTerm& x) { return x.key; }))
    sums.add(term);
  return sums;
}

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
  for (int a = 0; a < 3; ++a) hi[a] = std::nextafter(hi[a] + std::fabs(hi[a]) * kLayoutTopRelPad, kInf);
  Decomposition d = bisect(centres, costs, ids, ranks, lo, hi);
  for (DomainBox& box : d.boxes)  // the outer faces to infinity
    for (int a = 0; a < 3; ++a) {
      if (box.lo[a] == lo[a]) box.lo[a] = -kInf;
      if (box.hi[a] == hi[a]) box.hi[a] = kInf;
    }
  return {std::move(d.boxes)};
}

World make_domain(const World& whole, const DomainLayout& layout, int rank, DomainRole& role) {
  World d;
  role = {};
  d.settings = whole.settings;
  d.templates = whole.templates;
  d.materials = whole.materials;
  d.material_pairs = whole.material_pairs;
  d.planes = whole.planes;
  d.motions = whole.motions;
  d.inflows = whole.inflows;
  d.inflow_states = whole.inflow_states;
  d.cell.now = whole.cell.now;
  d.cell.rate = whole.cell.rate;
  d.cell.stress = whole.cell.stress;
  d.search.cell = whole.search.cell;
  d.search.renew_cell = whole.search.renew_cell;
  role.whole_reach = largest_reach(whole);
  d.bonds = whole.bonds;
  role.bonds_told.resize(whole.bonds.size());
  for (std::size_t k = 0; k < whole.bonds.size(); ++k) role.bonds_told[k] = whole.bonds[k].intact;
  d.time = whole.time;
  d.forces_current = whole.forces_current;
  d.wall_work = whole.wall_work;
  d.split_energy = whole.split_energy;
  d.applied_loads = whole.applied_loads;
  d.stats = whole.stats;
  const BoxCache& boxes = whole.search.boxes;
  const bool boxed = boxes.anchor_position.size() == whole.bodies.size() && boxes.boxes.size() == whole.bodies.size();
  std::vector<std::uint64_t> mine;
  for (std::size_t i = 0; i < whole.bodies.size(); ++i) {
    const Body& b = whole.bodies[i];
    const bool own = !b.fixed && layout.owner_of(b.position) == rank;
    if (!b.fixed && !own) continue;
    d.bodies.push_back(b);
    role.foreign.push_back(own ? 0 : 1);
    if (own) mine.push_back(b.id);
    if (boxed) {
      d.search.boxes.boxes.push_back(boxes.boxes[i]);
      d.search.boxes.anchor_position.push_back(boxes.anchor_position[i]);
      d.search.boxes.anchor_orientation.push_back(boxes.anchor_orientation[i]);
    }
  }
  d.search.boxes.moved.resize(d.search.boxes.boxes.size());
  for (DrivenBody driven : whole.driven) {
    driven.body = static_cast<std::uint32_t>(index_of_body(d.bodies, whole.bodies[driven.body].id));
    d.driven.push_back(driven);
  }
  for (const PairState& p : whole.pairs)
    if (std::binary_search(mine.begin(), mine.end(), p.key.lo) || std::binary_search(mine.begin(), mine.end(), p.key.hi))
      d.pairs.push_back(p);
  return d;
}

std::vector<Real> body_costs(const World& w) {
  std::vector<Real> cost(w.bodies.size(), 1);
  auto count = [&](std::uint64_t id) {
    if (const std::size_t i = index_of_body(w.bodies, id); i < cost.size()) cost[i] += 1;
  };
  for (const PairState& p : w.pairs) count(p.key.lo), count(p.key.hi);
  return cost;
}

void gather_world(const World& d, const DomainRole& role, DomainTransport& t, World& whole) {
  std::vector<BodyRecord> bodies;
  std::vector<ContactRecord> contacts;
  for (std::size_t i = 0; i < d.bodies.size(); ++i)
    if (role.owns(i) || (t.rank() == 0 && d.bodies[i].fixed)) bodies.push_back(record_of(d, i));
  for (std::size_t k = 0; k < d.results.contacts.size(); ++k) {
    const StepContact& c = d.results.contacts[k];
    if (!c.active) continue;
    ContactRecord r{d.results.keys[k], c.a_is_plane ? c.a : d.bodies[c.a].id, d.bodies[c.b].id, c};
    contacts.push_back(r);
  }
  std::vector<PairState> pairs;  // with an owned body (a domain lists no other)
  pairs.reserve(d.pairs.size());
  pairs.insert(pairs.end(), d.pairs.begin(), d.pairs.end());
  // Each bond's energy from the domain that owns its first body (which
  // holds the second: exchange_bodies), summed below in bond order.
  std::vector<BondEnergy> bond_energies;
  if (d.results.bond_energies.size() == d.bonds.size())
    for (std::size_t k = 0; k < d.bonds.size(); ++k) {
      const std::size_t a = index_of_body(d.bodies, d.bonds[k].a);
      if (a < d.bodies.size() && role.owns(a))
        bond_energies.push_back({k, d.results.bond_energies[k]});
    }
  Writer m;
  m.put(bodies), m.put(pairs), m.put(contacts), m.put(bond_energies);
  const std::vector<std::string> in = gather_to_root(t, m.take());
  if (t.rank() != 0) return;
  bodies.clear(), pairs.clear(), contacts.clear(), bond_energies.clear();
  for (const std::string& message : in) {
    Reader r(message);
    r.get(bodies), r.get(pairs), r.get(contacts), r.get(bond_energies);
  }
  std::sort(bodies.begin(), bodies.end(), [](const BodyRecord& x, const BodyRecord& y) { return x.body.id < y.body.id; });
  sort_unique(pairs, [](const PairState& p) { return p.key; });
  sort_unique(contacts, [](const ContactRecord& c) { return c.key; });
  const std::size_t n = bodies.size();
  whole.bodies.resize(n);
  BoxCache& boxes = whole.search.boxes;
  boxes.boxes.resize(n), boxes.anchor_position.resize(n), boxes.anchor_orientation.resize(n), boxes.moved.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyRecord& r = bodies[i];
    whole.bodies[i] = r.body;
    boxes.boxes[i] = r.box, boxes.anchor_position[i] = r.anchor_position, boxes.anchor_orientation[i] = r.anchor_orientation;
  }
  auto index_of = [&](std::uint64_t id) { return static_cast<std::uint32_t>(index_of_body(whole.bodies, id)); };
  whole.pairs = std::move(pairs);
  whole.inflow_states = d.inflow_states;  // the same on every rank
  // Fragments of broken grains: every domain holds every template.
  for (std::size_t k = whole.templates.size(); k < d.templates.size(); ++k) whole.templates.push_back(d.templates[k]);
  whole.broken = d.broken;
  whole.planes = d.planes;  // where their motions have them
  whole.results.motion_frames = d.results.motion_frames;
  whole.time = d.time;
  whole.forces_current = d.forces_current;
  whole.wall_work = d.wall_work;
  whole.split_energy = d.split_energy;  // rank 0's, as wall_work
  // The stats and the fixed bodies' reactions, summed as one rank sums
  // them (force_sums.cpp, contact_sums.hpp): in the order of the contact
  // list, which is the order of keys.
  whole.results.contacts.clear(), whole.results.keys.clear();
  for (Body& b : whole.bodies)
    if (b.fixed) b.force = b.torque = {};
  ContactSums sums;
  for (ContactRecord& r : contacts) {
    StepContact& c = r.contact;
    c.a = c.a_is_plane ? static_cast<std::uint32_t>(r.a) : index_of(r.a);
    c.b = index_of(r.b);
    Body& b = whole.bodies[c.b];
    const Vec3 shift = image_shift_of(d.cell.now, c);
    if (b.fixed) push_b(b, c, shift);
    if (!c.a_is_plane && whole.bodies[c.a].fixed) push_a(whole.bodies[c.a], c);
    sums.add(contact_term(c, shift, whole.bodies, whole.planes, whole.results.motion_frames, d.cell.now, d.cell.rate));
    whole.results.contacts.push_back(c);
    whole.results.keys.push_back(r.key);
  }
  StepStats stats = sums.stats();
  // The bonds' energy, as step.cpp adds it: summed in bond order, then
  // added to the contacts' (a bond broken or not found counts 0).
  whole.bonds = d.bonds;  // every rank's copy agrees (sync_bonds)
  if (any_intact(whole.bonds)) {
    std::vector<Real> energy(whole.bonds.size(), 0);
    for (const BondEnergy& e : bond_energies)
      if (e.bond < energy.size()) energy[e.bond] = e.joules;
    Real sum = 0;
    for (std::size_t k = 0; k < energy.size(); ++k)
      if (whole.bonds[k].intact) sum += energy[k];
    stats.elastic_energy += sum;
  }
  stats.wall_power = d.stats.wall_power;  // rank 0's is the whole world's (whole_wall_power), the sums' the same
  whole.stats = stats;
  whole.cell.now = d.cell.now;
  whole.cell.rate = d.cell.rate;
  whole.search.cell = d.search.cell;
  whole.search.renew_cell = d.search.renew_cell;
  if (d.cell.now.active()) whole.cell.stress = sums.cell_stress(whole.cell.now);
  whole.work.candidates_current = false;
}

Real whole_wall_power(const World& d, DomainTransport& t) {
  constexpr std::uint8_t kPowered = kTermImage | kTermDrivenA | kTermDrivenB;
  return gathered_sums(d, t, [](const ContactTerm& x) { return (x.holds & kPowered) != 0; }).stats().wall_power;
}

Real whole_contact_energy(const World& d, DomainTransport& t) {
  return gathered_sums(d, t, [](const ContactTerm&) { return true; }).stats().elastic_energy;
}

CellTensor whole_cell_stress(const World& d, DomainTransport& t) {
  CellTensor stress = gathered_sums(d, t, [](const ContactTerm&) { return true; }).cell_stress(d.cell.now);
  const std::string said = all_gather(t, std::string(reinterpret_cast<const char*>(stress.data()), sizeof stress))[0];
  if (said.size() != sizeof stress) throw std::runtime_error("the cell's stress came damaged");
  std::memcpy(stress.data(), said.data(), sizeof stress);
  return stress;
}

void add_field_work(World& d, DomainRole& role, DomainTransport& t) {
  using Term = FieldWork;
  Writer m;
  m.put(role.field_work), m.put(role.wrap_work);
  role.field_work.clear(), role.wrap_work.clear();
  const std::vector<std::string> in = gather_to_root(t, m.take());
  if (t.rank() != 0) return;
  std::vector<Term> changes, wraps;
  for (const std::string& message : in) {
    Reader r(message);
    r.get(changes), r.get(wraps);
  }
  for (std::vector<Term>* terms : {&changes, &wraps}) {
    if (terms->empty()) continue;  // as a whole world, which adds nothing then
    sort_unique(*terms, [](const Term& f) { return f.id; });
    Real added = 0;  // body by body, in id order
    for (const Term& f : *terms) added += f.joules;
    d.wall_work += added;
  }
}

}  // namespace gjkdem::dem
