#pragma once
// What domains send each other (domains.cpp, domain_exchange.cpp): arrays of
// plain records copied as bytes, every rank running the same build.
#include <algorithm>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "gjkdem/dem/domains.hpp"
#include "gjkdem/dem/world.hpp"

namespace gjkdem::dem::detail {

// A body as it travels: its state and its box with the box's anchors.
struct BodyRecord {
  Body body;
  Aabb box;
  Vec3 anchor_position;
  Quat anchor_orientation;
};

/// A bond's energy at the last force evaluation (J), by its index in
/// World::bonds; and a bond broken at `time` (s).
struct BondEnergy {
  std::uint64_t bond = 0;
  Real joules = 0;
};
struct BondBroken {
  std::uint64_t bond = 0;
  Real time = 0;
};

/// Every rank's message, by rank, on rank 0 (none elsewhere).
inline std::vector<std::string> gather_to_root(DomainTransport& t, std::string mine) {
  std::vector<std::string> out(static_cast<std::size_t>(t.size()));
  out[0] = std::move(mine);
  std::vector<std::string> in = t.exchange(std::move(out));
  if (t.rank() != 0) in.clear();
  return in;
}

static_assert(std::is_trivially_copyable_v<BodyRecord> && std::is_trivially_copyable_v<PairState>);

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
    if (n > (bytes_.size() - at_) / sizeof(T)) throw std::runtime_error("a domain message is shorter than its contents");
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

inline BodyRecord record_of(const World& w, std::size_t i) {
  const BoxCache& c = w.search.boxes;
  return {w.bodies[i], c.boxes[i], c.anchor_position[i], c.anchor_orientation[i]};
}

// How many of `bodies` (in increasing id order) have an id below `id`.
inline std::size_t count_ids_below(std::span<const Body> bodies, std::uint64_t id) {
  return static_cast<std::size_t>(
      std::lower_bound(bodies.begin(), bodies.end(), id, [](const Body& b, std::uint64_t v) { return b.id < v; }) -
      bodies.begin());
}


// Replaces the domain's bodies and boxes by `records` (any order).
inline void set_bodies(World& w, DomainRole& role, std::vector<BodyRecord>& records,
                       std::span<const std::uint8_t> foreign_of_record) {
  std::vector<std::uint64_t> driven_ids;  // driven bodies are fixed: every domain holds them
  for (const DrivenBody& d : w.driven) driven_ids.push_back(w.bodies[d.body].id);
  std::vector<std::uint32_t> order(records.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t p, std::uint32_t q) { return records[p].body.id < records[q].body.id; });
  const std::size_t n = records.size();
  BoxCache& c = w.search.boxes;
  w.bodies.resize(n);
  c.boxes.resize(n), c.anchor_position.resize(n), c.anchor_orientation.resize(n), c.moved.resize(n);
  role.foreign.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const BodyRecord& r = records[order[i]];
    w.bodies[i] = r.body;
    c.boxes[i] = r.box, c.anchor_position[i] = r.anchor_position, c.anchor_orientation[i] = r.anchor_orientation;
    role.foreign[i] = foreign_of_record[order[i]];
  }
  for (std::size_t k = 0; k < w.driven.size(); ++k) w.driven[k].body = static_cast<std::uint32_t>(index_of_body(w.bodies, driven_ids[k]));
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

inline bool same_bits(const void* a, const void* b, std::size_t n) { return std::memcmp(a, b, n) == 0; }

}  // namespace gjkdem::dem::detail
