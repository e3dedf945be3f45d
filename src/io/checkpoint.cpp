#include "gjkdem/io/checkpoint.hpp"

#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>

#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/dem/boxes.hpp"
#include "gjkdem/dem/breakage.hpp"
#include "gjkdem/io/run_output.hpp"

namespace gjkdem::io {
namespace {

constexpr char kMagic[8] = {'G', 'J', 'K', 'D', 'E', 'M', 'C', 'K'};
constexpr std::uint32_t kHeaderBytes = 40;
constexpr const char* kInfo =
    "gjkdem checkpoint, format 11. Little-endian; reals are IEEE-754 binary64, counts u64. Sections (tag, u64 "
    "length): RUN dt steps_total steps_per_output step outputs initial_energy time; STAT forces_current(u8) "
    "elastic_energy contacts(u64) wall_contacts(u64) wall_power wall_work split_energy applied_loads(u8); CELL periodic cell lo(3) hi(3) tilt(3) "
    "velocity gradient(6) stress(6), cell of the last candidate search lo(3) hi(3) tilt(3); MAKE count, per shape "
    "template the builder made digest(u64), count, per plane wall digest(u64); FRAG grains broken(u64) count, per "
    "fragment template generation(u32) surface(u8) count, per hull vertex (3); BODY count, per column name(u64 "
    "length, bytes) components(u32), count, per body id(u64) shape(u32) material(u32) then each column's reals; FLOW "
    "count, per inflow inserted(u64) attempts(u64) mass energy behind(u64); BOXS count, per body anchor position(3) and "
    "orientation(4); PAIR count, per pair key(lo,hi u64, parts u32) gjk dirs(4x3) size(u32) hint_a(u32) hint_b(u32) "
    "spring(3) twist roll(3) patch anchor(3); BOND count, per bond a(u64) b(u64) intact(u8) broken_time; LOGS trace_bytes(u64) energy_bytes(u64) cell_bytes(u64) wall_seconds count, per frame name(u64 "
    "length, bytes) time.";

class Out {
 public:
  void u8(std::uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void u64(std::uint64_t v) {
    for (int k = 0; k < 8; ++k) u8(static_cast<std::uint8_t>(v >> (8 * k)));
  }
  void real(Real v) { u64(std::bit_cast<std::uint64_t>(v)); }
  void vec(const Vec3& v) { real(v.x), real(v.y), real(v.z); }
  void quat(const Quat& q) { real(q.w), real(q.x), real(q.y), real(q.z); }
  void text(std::string_view s) {
    u64(s.size());
    bytes_.append(s);
  }
  // A section: tag, then its length patched in when it ends.
  std::size_t begin(const char (&tag)[5]) {
    bytes_.append(tag, 4);
    const std::size_t at = bytes_.size();
    u64(0);
    return at;
  }
  void end(std::size_t at) {
    const std::uint64_t length = bytes_.size() - at - 8;
    for (int k = 0; k < 8; ++k) bytes_[at + k] = static_cast<char>(static_cast<std::uint8_t>(length >> (8 * k)));
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class In {
 public:
  In(std::string_view bytes, std::string name) : bytes_(bytes), name_(std::move(name)) {}
  [[noreturn]] void fail(const std::string& what) const {
    throw CheckpointError(name_ + ": damaged checkpoint (" + what + ")");
  }
  std::uint8_t u8() {
    need(1);
    return static_cast<std::uint8_t>(bytes_[at_++]);
  }
  std::uint32_t u32() {
    need(4);
    std::uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= std::uint32_t{static_cast<std::uint8_t>(bytes_[at_++])} << (8 * k);
    return v;
  }
  std::uint64_t u64() {
    need(8);
    std::uint64_t v = 0;
    for (int k = 0; k < 8; ++k) v |= std::uint64_t{static_cast<std::uint8_t>(bytes_[at_++])} << (8 * k);
    return v;
  }
  Real real() { return std::bit_cast<Real>(u64()); }
  Vec3 vec() {
    const Real x = real(), y = real(), z = real();
    return {x, y, z};
  }
  Quat quat() {
    const Real w = real(), x = real(), y = real(), z = real();
    return {w, x, y, z};
  }
  std::string text() {
    const std::uint64_t n = u64();
    need(n);
    std::string s(bytes_.substr(at_, n));
    at_ += n;
    return s;
  }
  // A count of records of at least `record` bytes each: it must fit in what is left.
  std::uint64_t count(std::uint64_t record) {
    const std::uint64_t n = u64();
    if (n > (bytes_.size() - at_) / record) fail("a count larger than the file");
    return n;
  }
  // Enters the section `tag`; returns where it ends.
  std::size_t section(const char (&tag)[5]) {
    need(4);
    if (bytes_.substr(at_, 4) != std::string_view(tag, 4)) fail(std::string("expected section ") + tag);
    at_ += 4;
    const std::uint64_t length = u64();
    need(length);
    return at_ + length;
  }
  void close(std::size_t end, const char* tag) {
    if (at_ != end) fail(std::string("section ") + tag + " has the wrong length");
  }
  std::size_t position() const { return at_; }
  void skip_to(std::size_t end) { at_ = end; }

 private:
  void need(std::uint64_t n) const {
    if (n > bytes_.size() - at_) fail("it ends early");
  }
  std::string_view bytes_;
  std::string name_;
  std::size_t at_ = 0;
};

// The FRAG section: grains broken so far and the fragments' templates.
struct Fragments {
  std::uint64_t broken = 0;
  std::vector<dem::ShapeTemplate> templates;
};
Fragments read_fragments(In& in) {
  const std::size_t end = in.section("FRAG");
  Fragments f;
  f.broken = in.u64();
  f.templates.resize(in.count(4 + 1 + 8));
  for (dem::ShapeTemplate& t : f.templates) {
    const std::uint32_t generation = in.u32();
    const bool surface = in.u8() != 0;
    std::vector<Vec3> vertices(in.count(3 * 8));
    for (Vec3& v : vertices) v = in.vec();
    if (generation == 0 || vertices.size() < 4) in.fail("a fragment's template is not valid");
    try {
      t = dem::fragment_template(make_polytope(vertices), generation, surface);
    } catch (const std::invalid_argument&) {
      in.fail("a fragment's template is not valid");
    }
    if (!(t.unit_mass.volume > 0)) in.fail("a fragment's template is not valid");
  }
  in.close(end, "FRAG");
  return f;
}

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) noexcept {
  std::uint64_t h = 14695981039346656037ull;
  for (const char c : bytes) {
    h ^= static_cast<std::uint8_t>(c);
    h *= 1099511628211ull;
  }
  return h;
}

// What a world is made of, as digests a restore compares: a template's
// kind, exact mass properties, reach and extreme points in 14 directions (its
// size and form), a plane wall's place as built. They tell a changed shape
// or wall apart from a changed material or law, which a continued run may
// take (docs/checkpoints.md, "Continuing with changes").
std::uint64_t digest(const dem::ShapeTemplate& t) {
  Out o;
  o.u32(static_cast<std::uint32_t>(t.shape.core.index())), o.real(t.shape.margin);
  o.real(t.unit_mass.volume), o.vec(t.unit_mass.centroid);
  for (const Vec3& r : t.unit_mass.inertia.row) o.vec(r);
  o.real(t.reach), o.u64(t.parts.size()), o.u8(t.surface_grain ? 1 : 0);
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if ((x != 0) + (y != 0) + (z != 0) != 2 && (x | y | z) != 0) o.vec(support(t.shape, Vec3{Real(x), Real(y), Real(z)}));
  for (const dem::TemplatePart& p : t.parts) {
    o.vec(p.pose.translation), o.real(p.volume), o.real(p.radius);
    if (p.surface_grain) o.u8(1), o.u64(p.surface->triangles.size());  // (nothing for a convex part: digests as before)
  }
  if (t.shell) {  // its triangles, not only its hull
    o.u8(2), o.real(t.shell->margin), o.u64(t.shell->triangles.size());
    for (const TriangleIndices& tri : t.shell->triangles) o.u32(tri[0]), o.u32(tri[1]), o.u32(tri[2]);
  }
  if (t.wall_face)
    for (const Vec3& v : t.wall_face->v) o.vec(v);
  return fnv1a64(o.bytes());
}

constexpr const char* kKeepAsItWas =
    " (a run goes on only with its bodies, shapes and walls as they were; materials, contact law settings, gravity, "
    "motions, duration and outputs may change)";

std::string body_text(const dem::World& w, std::uint64_t id) {
  for (const dem::BodyName& n : w.names)
    if (n.id == id) return "body " + std::to_string(id) + " ('" + n.name + "')";
  return "body " + std::to_string(id);
}

std::uint64_t digest(const dem::PlaneWall& p) {
  Out o;
  o.vec(p.given_point), o.vec(p.given_normal);
  return fnv1a64(o.bytes());
}

std::string encode_checkpoint(const dem::World& w, const Checkpoint& c, std::uint64_t fingerprint) {
  Out o;
  std::size_t s = o.begin("INFO");
  o.bytes().append(kInfo);
  o.end(s);
  s = o.begin("RUN ");
  o.real(c.run.dt), o.u64(c.run.steps_total), o.u64(c.run.steps_per_output), o.u64(c.run.step), o.u64(c.run.outputs);
  o.real(c.run.initial_energy), o.real(w.time);
  o.end(s);
  s = o.begin("STAT");
  o.u8(w.forces_current ? 1 : 0), o.real(w.stats.elastic_energy);
  o.u64(static_cast<std::uint64_t>(w.stats.contacts)), o.u64(static_cast<std::uint64_t>(w.stats.wall_contacts));
  o.real(w.stats.wall_power), o.real(w.wall_work), o.real(w.split_energy), o.u8(w.applied_loads ? 1 : 0);
  o.end(s);
  s = o.begin("CELL");
  o.vec(w.cell.now.lo), o.vec(w.cell.now.hi), o.vec(w.cell.now.tilt);
  for (const Real v : w.cell.rate) o.real(v);
  for (const Real v : w.cell.stress) o.real(v);
  o.vec(w.search.cell.lo), o.vec(w.search.cell.hi), o.vec(w.search.cell.tilt);
  o.end(s);
  const std::size_t built = dem::built_templates(w);
  s = o.begin("MAKE");
  o.u64(built);
  for (std::size_t k = 0; k < built; ++k) o.u64(digest(w.templates[k]));
  o.u64(w.planes.size());
  for (const dem::PlaneWall& p : w.planes) o.u64(digest(p));
  o.end(s);
  s = o.begin("FRAG");  // fragments' templates in full: a restore makes them again with the same bits
  o.u64(w.broken), o.u64(w.templates.size() - built);
  for (std::size_t k = built; k < w.templates.size(); ++k) {
    const dem::ShapeTemplate& t = w.templates[k];
    o.u32(t.generation), o.u8(t.surface ? 1 : 0);
    const std::span<const Vec3> vertices = std::get<Polytope>(t.shape.core).data->vertices;
    o.u64(vertices.size());
    for (const Vec3& v : vertices) o.vec(v);
  }
  o.end(s);
  s = o.begin("BODY");  // the saved channels of body_channels.hpp, named
  std::vector<const dem::BodyChannel*> saved;
  for (const dem::BodyChannel& ch : dem::kBodyChannels)
    if (ch.use & dem::kChannelSaved) saved.push_back(&ch);
  o.u64(saved.size());
  for (const dem::BodyChannel* ch : saved) o.text(ch->name), o.u32(ch->components);
  o.u64(w.bodies.size());
  for (const dem::Body& b : w.bodies) {
    o.u64(b.id), o.u32(b.shape), o.u32(b.material);
    for (const dem::BodyChannel* ch : saved)
      for (std::uint32_t k = 0; k < ch->components; ++k) o.real(ch->in(b)[k]);
  }
  o.end(s);
  s = o.begin("FLOW");
  o.u64(w.inflow_states.size());
  for (const dem::InflowState& f : w.inflow_states) o.u64(f.inserted), o.u64(f.attempts), o.real(f.mass), o.real(f.energy), o.u64(f.behind);
  o.end(s);
  s = o.begin("BOXS");
  const dem::BoxCache& boxes = w.search.boxes;
  const bool has_boxes = boxes.anchor_position.size() == w.bodies.size();
  o.u64(has_boxes ? w.bodies.size() : 0);
  if (has_boxes)
    for (std::size_t i = 0; i < w.bodies.size(); ++i) o.vec(boxes.anchor_position[i]), o.quat(boxes.anchor_orientation[i]);
  o.end(s);
  s = o.begin("PAIR");
  o.u64(w.pairs.size());
  for (const dem::PairState& p : w.pairs) {
    o.u64(p.key.lo), o.u64(p.key.hi), o.u32(p.key.parts);
    for (const Vec3& d : p.gjk.dirs) o.vec(d);
    o.u32(static_cast<std::uint32_t>(p.gjk.size)), o.u32(static_cast<std::uint32_t>(p.gjk.hint_a));
    o.u32(static_cast<std::uint32_t>(p.gjk.hint_b));
    o.vec(p.history.spring), o.real(p.history.twist), o.vec(p.history.roll), o.vec(p.anchor);
  }
  o.end(s);
  s = o.begin("BOND");  // what a bond's state holds beyond what the builder made: whether it broke, and when
  o.u64(w.bonds.size());
  for (const dem::Bond& b : w.bonds) o.u64(b.a), o.u64(b.b), o.u8(b.intact), o.real(b.broken_time);
  o.end(s);
  s = o.begin("LOGS");
  o.u64(c.logs.trace_bytes), o.u64(c.logs.energy_bytes), o.u64(c.logs.cell_bytes), o.real(c.logs.wall_seconds);
  o.u64(c.logs.frames.size());
  for (const auto& [name, time] : c.logs.frames) o.text(name), o.real(time);
  o.end(s);

  Out head;
  head.bytes().append(kMagic, sizeof kMagic);
  head.u32(kCheckpointVersion), head.u32(kHeaderBytes);
  head.u64(o.bytes().size()), head.u64(fnv1a64(o.bytes())), head.u64(fingerprint);
  return head.bytes() + o.bytes();
}

namespace {

// The payload of a checkpoint whose magic, format, length and checksum are
// right, and the scene fingerprint its header holds.
std::pair<std::string_view, std::uint64_t> checked_payload(std::string_view bytes, const std::string& name) {
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    if (bytes.size() >= 7 && bytes.substr(0, 7) == "gjkdckp")
      throw CheckpointError(name + " is a checkpoint of an older gjkdem format; this gjkdem reads format " +
                           std::to_string(kCheckpointVersion) + " (restart the run without --resume)");
    throw CheckpointError(name + " is not a gjkdem checkpoint");
  }
  In head(bytes.substr(sizeof kMagic), name);
  const std::uint32_t version = head.u32();
  if (version != kCheckpointVersion)
    throw CheckpointError(name + " has checkpoint format " + std::to_string(version) + "; this gjkdem reads format " +
                          std::to_string(kCheckpointVersion) + " (restart the run without --resume)");
  if (head.u32() != kHeaderBytes) head.fail("header length");
  const std::uint64_t length = head.u64(), checksum = head.u64(), scene = head.u64();
  const std::string_view payload = bytes.substr(kHeaderBytes);
  if (payload.size() != length) head.fail("its length does not match its header: truncated or extended");
  if (fnv1a64(payload) != checksum) head.fail("its checksum does not match");
  return {payload, scene};
}

}  // namespace

Checkpoint decode_checkpoint(std::string_view bytes, dem::World& w, std::uint64_t fingerprint, const std::string& name,
                             Restore how) {
  const auto [payload, scene] = checked_payload(bytes, name);
  if (how == Restore::SameRun && scene != fingerprint)
    throw CheckpointError(name + " was written for another scene (or the scene file changed since): refusing to "
                          "continue it as the same run; a new run may start from its state with changed materials, "
                          "contact law, gravity, duration or outputs (gjkdem run SCENE --from RUN_FOLDER; Python: "
                          "load_checkpoint(path, restart=True))");

  In in(payload, name);
  Checkpoint c;
  std::size_t end = in.section("INFO");
  while (in.position() < end) in.u8();
  end = in.section("RUN ");
  c.run.dt = in.real(), c.run.steps_total = in.u64(), c.run.steps_per_output = in.u64(), c.run.step = in.u64();
  c.run.outputs = in.u64(), c.run.initial_energy = in.real();
  const Real time = in.real();
  in.close(end, "RUN");
  if (!(c.run.dt > 0) || !std::isfinite(c.run.dt) || !std::isfinite(time) || !std::isfinite(c.run.initial_energy) ||
      c.run.steps_per_output == 0 || c.run.step > c.run.steps_total)
    in.fail("the run's clock is not valid");
  end = in.section("STAT");
  const bool forces_current = in.u8() != 0;
  dem::StepStats stats;
  stats.elastic_energy = in.real();
  stats.contacts = static_cast<int>(in.u64());
  stats.wall_contacts = static_cast<int>(in.u64());
  stats.wall_power = in.real();
  const Real wall_work = in.real();
  const Real split_energy = in.real();
  const std::uint8_t applied_loads = in.u8();
  in.close(end, "STAT");
  if (applied_loads > 1) in.fail("the applied loads' flag is not 0 or 1");
  if (!std::isfinite(stats.wall_power) || !std::isfinite(wall_work)) in.fail("the work of driven walls is not finite");
  if (!std::isfinite(split_energy)) in.fail("the energy the splits stored is not finite");
  end = in.section("CELL");
  dem::PeriodicCell cell = w.settings.periodic, searched = w.settings.periodic;
  cell.lo = in.vec(), cell.hi = in.vec(), cell.tilt = in.vec();
  dem::CellTensor rate, stress;
  for (Real& v : rate) v = in.real();
  for (Real& v : stress) v = in.real();
  searched.lo = in.vec(), searched.hi = in.vec(), searched.tilt = in.vec();
  in.close(end, "CELL");
  bool valid = std::isfinite(cell.tilt.x) && std::isfinite(cell.tilt.y) && std::isfinite(cell.tilt.z);
  for (int k = 0; k < 6; ++k) valid = valid && std::isfinite(rate[k]) && std::isfinite(stress[k]);
  for (int a = 0; a < 3; ++a)
    if (cell.axes[a]) valid = valid && cell.hi[a] > cell.lo[a] && std::isfinite(cell.lo[a]) && std::isfinite(cell.hi[a]);
  if (!valid) in.fail("the periodic cell is not valid");

  // What the world is made of must be as it was: its shapes and walls (by
  // digest). Materials and settings are not compared: a run may go on with
  // other ones.
  const auto refuse = [&](const std::string& what) {
    throw CheckpointError(name + ": " + what + kKeepAsItWas);
  };
  end = in.section("MAKE");
  std::vector<std::uint64_t> shapes(in.count(8));
  for (std::uint64_t& d : shapes) d = in.u64();
  std::vector<std::uint64_t> planes(in.count(8));
  for (std::uint64_t& d : planes) d = in.u64();
  in.close(end, "MAKE");
  if (planes.size() != w.planes.size())
    refuse("the scene has " + std::to_string(w.planes.size()) + " plane walls, the checkpoint " +
           std::to_string(planes.size()));
  for (std::size_t k = 0; k < planes.size(); ++k)
    if (planes[k] != digest(w.planes[k])) refuse("plane wall " + std::to_string(k) + " is not where it was built");
  Fragments made = read_fragments(in);
  const std::uint64_t broken = made.broken;
  std::vector<dem::ShapeTemplate>& fragments = made.templates;
  const std::size_t scene_templates = dem::built_templates(w);
  const std::size_t all_templates = scene_templates + fragments.size();

  // Into a copy: the world is changed only once everything has been read.
  // Bodies beyond the scene's were inserted by its inflows: moving, of the
  // inflows' templates (checked against the FLOW counts below).
  std::vector<dem::Body> bodies = w.bodies;
  end = in.section("BODY");
  // Its columns, found by name: a channel the checkpoint lacks keeps the
  // scene's value (a body inserted since: none).
  std::vector<const dem::BodyChannel*> columns(in.count(8 + 4));
  std::uint64_t row_reals = 0;
  for (const dem::BodyChannel*& column : columns) {
    const std::string label = in.text();
    const std::uint32_t components = in.u32();
    column = dem::find_body_channel(label);
    if (!column || !(column->use & dem::kChannelSaved))
      throw CheckpointError(name + ": its bodies have a column '" + label +
                            "' this gjkdem does not know (written by a newer gjkdem?)");
    if (column->components != components) in.fail("the column '" + label + "' has the wrong number of components");
    row_reals += components;
  }
  for (std::size_t k = 0; k < columns.size(); ++k)
    for (std::size_t j = 0; j < k; ++j)
      if (columns[j] == columns[k]) in.fail("the column '" + std::string(columns[k]->name) + "' twice");
  for (const dem::BodyChannel& ch : dem::kBodyChannels)
    if ((ch.use & dem::kChannelRequired) && std::find(columns.begin(), columns.end(), &ch) == columns.end())
      in.fail("its bodies have no column '" + std::string(ch.name) + "'");
  const std::uint64_t count = in.count(8 + 2 * 4 + row_reals * 8);
  if (count < bodies.size() || (count > bodies.size() && w.inflows.empty() && broken == 0))
    refuse("the scene has " + std::to_string(bodies.size()) + " bodies, the checkpoint " + std::to_string(count) +
           (count > bodies.size() ? " (and the scene has no inflow to have inserted them)" : ""));
  if (shapes.size() != scene_templates)
    refuse("the scene has " + std::to_string(scene_templates) + " shape templates, the checkpoint " +
           std::to_string(shapes.size()));
  std::vector<bool> changed(shapes.size());
  for (std::size_t k = 0; k < shapes.size(); ++k) changed[k] = shapes[k] != digest(w.templates[k]);
  const std::size_t scene_bodies = bodies.size();
  std::string differs;  // the first body that is not as it was
  bodies.resize(count);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    dem::Body& b = bodies[i];
    const std::uint64_t id = in.u64();
    const std::uint32_t shape = in.u32(), material = in.u32();
    if (shape >= all_templates) in.fail("a body's shape out of range");
    const bool fragment = shape >= scene_templates;  // the grain broke: its place and id kept by a fragment
    if (i < scene_bodies) {
      if (id != b.id && differs.empty())
        differs = body_text(w, b.id) + " is body " + std::to_string(id) + " in the checkpoint";
      if (fragment && b.fixed) in.fail("a fixed body has a fragment's shape");
      if (fragment) b.shape = shape;
      if (!fragment && (shape != b.shape || changed[shape]) && differs.empty())
        differs = body_text(w, b.id) + " has another shape than in the checkpoint";
    }
    if (i >= scene_bodies) {
      if ((i > 0 && !(id > bodies[i - 1].id)) || id >= dem::kPlaneIdBase || material >= w.materials.size())
        in.fail("an inserted body out of range");
      b = dem::Body{};
      b.id = id, b.shape = shape, b.material = material;
    }
    dem::Body saved = b;
    for (const dem::BodyChannel* column : columns)
      for (std::uint32_t k = 0; k < column->components; ++k) column->in(saved)[k] = in.real();
    const Vec3& position = saved.position;
    const Quat& orientation = saved.orientation;
    if (b.fixed && b.motion == 0 &&
        !(position == b.position && orientation.w == b.orientation.w && orientation.x == b.orientation.x &&
          orientation.y == b.orientation.y && orientation.z == b.orientation.z))
      if (differs.empty()) differs = body_text(w, b.id) + " (fixed) is not where it was in the checkpoint";
    b = saved;
  }
  in.close(end, "BODY");
  end = in.section("FLOW");
  if (in.count(5 * 8) != w.inflows.size())
    throw CheckpointError(name + ": the scene has a different number of inflows than the checkpoint");
  std::vector<dem::InflowState> flows(w.inflows.size());
  std::uint64_t inserted = 0;
  for (dem::InflowState& f : flows) {
    f.inserted = in.u64(), f.attempts = in.u64(), f.mass = in.real(), f.energy = in.real(), f.behind = in.u64();
    inserted += f.inserted;
  }
  in.close(end, "FLOW");
  std::uint64_t inserted_before = 0;  // by the scene's own world (a continued one)
  for (const dem::InflowState& f : w.inflow_states) inserted_before += f.inserted;
  // Bodies beyond the scene's came from its inflows and from grains that broke.
  if (inserted < inserted_before || broken < w.broken ||
      (inserted - inserted_before) + (broken - w.broken) != count - scene_bodies)
    refuse("the scene has " + std::to_string(scene_bodies) + " bodies, the checkpoint " + std::to_string(count) +
           " of which its inflows inserted " + std::to_string(inserted - std::min(inserted, inserted_before)) +
           " and broken grains made " + std::to_string(broken - std::min(broken, w.broken)));
  // The first body found to differ is named once the counts are known to agree.
  if (!differs.empty()) refuse(differs);
  for (std::size_t k = 0; k < shapes.size(); ++k)
    if (changed[k]) refuse("shape template " + std::to_string(k) + " (of an inflow) differs from the checkpoint's");
  end = in.section("BOXS");
  const std::uint64_t anchors = in.count(7 * 8);
  if (anchors != 0 && anchors != bodies.size()) in.fail("box anchors do not match the bodies");
  dem::BoxCache boxes;
  for (std::uint64_t i = 0; i < anchors; ++i) {
    boxes.anchor_position.push_back(in.vec());
    boxes.anchor_orientation.push_back(in.quat());
  }
  in.close(end, "BOXS");
  end = in.section("PAIR");
  std::vector<dem::PairState> pairs(in.count(2 * 8 + 4 + 12 * 8 + 3 * 4 + 10 * 8));
  for (dem::PairState& p : pairs) {
    p.key.lo = in.u64(), p.key.hi = in.u64(), p.key.parts = in.u32();
    for (Vec3& d : p.gjk.dirs) d = in.vec();
    p.gjk.size = static_cast<int>(in.u32()), p.gjk.hint_a = static_cast<int>(in.u32());
    p.gjk.hint_b = static_cast<int>(in.u32());
    if (p.gjk.size < 0 || p.gjk.size > 4) in.fail("a warm start out of range");
    p.history.spring = in.vec(), p.history.twist = in.real(), p.history.roll = in.vec(), p.anchor = in.vec();
  }
  for (std::size_t k = 1; k < pairs.size(); ++k)
    if (!(pairs[k - 1].key < pairs[k].key)) in.fail("pairs out of order");
  in.close(end, "PAIR");
  end = in.section("BOND");
  std::vector<dem::Bond> bonds = w.bonds;
  if (const std::uint64_t saved = in.count(2 * 8 + 1 + 8); saved != bonds.size())
    refuse("the scene has " + std::to_string(bonds.size()) + " bonds, the checkpoint " + std::to_string(saved));
  for (dem::Bond& b : bonds) {
    const std::uint64_t a = in.u64(), other = in.u64();
    if (a != b.a || other != b.b) refuse("the bond of bodies " + std::to_string(b.a) + " and " + std::to_string(b.b) +
                                         " is another bond in the checkpoint");
    const std::uint8_t intact = in.u8();
    const Real when = in.real();
    if (intact > 1 || !std::isfinite(when)) in.fail("a bond's state is not valid");
    b.intact = intact, b.broken_time = when;
  }
  in.close(end, "BOND");
  end = in.section("LOGS");
  c.logs.trace_bytes = in.u64(), c.logs.energy_bytes = in.u64(), c.logs.cell_bytes = in.u64();
  c.logs.wall_seconds = in.real();
  c.logs.frames.resize(in.count(16));
  for (auto& [frame, t] : c.logs.frames) frame = in.text(), t = in.real();
  in.close(end, "LOGS");
  if (in.position() != payload.size()) in.fail("bytes after the last section");

  w.bodies.assign(bodies.begin(), bodies.end());  // in place: views of the bodies stay valid
  w.templates.resize(scene_templates);
  for (dem::ShapeTemplate& t : fragments) w.templates.push_back(std::move(t));
  w.broken = broken;
  w.inflow_states = std::move(flows);
  w.pairs = std::move(pairs);
  w.bonds = std::move(bonds);
  w.time = time;
  w.forces_current = forces_current;
  w.stats = stats;
  w.wall_work = wall_work;
  w.split_energy = split_energy;
  w.applied_loads = w.applied_loads || applied_loads != 0;
  if (how == Restore::NewRun) {  // a new clock; forces under the new settings
    w.time = 0, w.wall_work = 0, w.split_energy = 0, w.forces_current = false;
    for (dem::Body& b : w.bodies) b.applied_work = 0;  // the loads stay, their work starts again
    c.logs = {};
  }
  w.cell.now = cell;
  w.cell.rate = rate;
  w.cell.stress = stress;
  w.results = {};  // the last evaluation's were the old state's: found again at the next
  w.work = {};
  w.search = {};  // a checkpoint without anchors leaves none of the world's old ones
  dem::place_driven(w);  // planes and motion frames (driven bodies come back as saved)
  if (anchors > 0) {
    w.search.boxes = std::move(boxes);
    w.search.cell = searched;
    w.search.renew_cell = !searched.active();
    dem::rebuild_boxes_at_anchors(w.bodies, w.templates, w.settings.box_skin, w.search.boxes);
  }
  return c;
}

void save_checkpoint(const std::filesystem::path& file, const dem::World& w, const Checkpoint& c,
                     std::uint64_t fingerprint) {
  write_file_atomically(file, encode_checkpoint(w, c, fingerprint));
}

void load_fragment_templates(const std::filesystem::path& file, dem::World& w) {
  const std::optional<std::string> bytes = read_file(file);
  if (!bytes) throw CheckpointError("cannot read checkpoint " + file.string());
  In in(checked_payload(*bytes, file.string()).first, file.string());
  // The sections before FRAG, skipped.
  in.skip_to(in.section("INFO")), in.skip_to(in.section("RUN ")), in.skip_to(in.section("STAT"));
  in.skip_to(in.section("CELL")), in.skip_to(in.section("MAKE"));
  Fragments made = read_fragments(in);
  w.templates.resize(dem::built_templates(w));
  for (dem::ShapeTemplate& t : made.templates) w.templates.push_back(std::move(t));
}

Checkpoint load_checkpoint(const std::filesystem::path& file, dem::World& w, std::uint64_t fingerprint, Restore how) {
  const std::optional<std::string> bytes = read_file(file);
  if (!bytes) throw CheckpointError("cannot read checkpoint " + file.string());
  return decode_checkpoint(*bytes, w, fingerprint, file.string(), how);
}

}  // namespace gjkdem::io
