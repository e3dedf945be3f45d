// The scene reader's bodies (scene_reader.hpp): [[body]] (bonded ones too),
// [[generator]] and [[inflow]], their regions and their mixes of shapes.
#include "scene_reader/scene_reader.hpp"

namespace gjkdem::io::detail {

void SceneReader::read_body(TableReader& r) {
  if (const toml::node* n = r.find("shape"); n && n->is_table()) {
    const toml::table& t = *n->as_table();
    if (t.get("type") && t.get("type")->value<std::string>() == std::optional<std::string>("bonded"))
      return read_bonded_body(r, t);
  }
  dem::BodyDef d;
  d.label = r.where();
  const std::optional<std::string> name = r.string("name");
  d.shape = read_shape(r, "shape");
  d.material = material_of(r);
  d.fixed = r.boolean("fixed", false);
  if (NamedShape* named = named_shape(r, "shape")) {  // one template for its moving bodies, one for its fixed ones
    std::int64_t& shared = d.fixed ? named->shared_fixed : named->shared;
    if (shared < 0) shared = building(r.table_node(), [&] { return builder_->add_shape(d.shape, d.label, d.fixed); });
    d.shared_shape = shared;
  }
  d.position = r.vec3_or("position", Vec3{});
  d.rotation = r.rotation_or("rotation", Quat{});
  d.velocity = r.vec3_or("velocity", Vec3{});
  d.angular_velocity = r.vec3_or("angular_velocity", Vec3{});
  if (d.fixed && (length(d.velocity) > 0 || length(d.angular_velocity) > 0))
    r.fail("velocity", "a fixed body cannot move (velocity and angular_velocity must be 0; give it a 'motion')");
  read_given_channels(r, d);
  if (r.has("motion") && !d.fixed) r.fail("motion", "is for fixed bodies (set fixed = true)");
  d.motion = read_motion(r);
  if (name && name->empty()) r.fail("name", "must not be empty (leave it out for an untraced body)");
  if (name) d.name = *name;  // the builder checks it (unique, a CSV field)
  const std::uint32_t index = building(r.table_node(), [&] { return builder_->add_body(d); });
  body_lines_[index] = r.table_node().source().begin.line;
}

// The body's given channels (kChannelGiven), each under its name; the
// builder checks their rules.
void SceneReader::read_given_channels(TableReader& r, dem::BodyDef& d) {
  for (const dem::BodyChannel& c : dem::kBodyChannels) {
    if (!(c.use & dem::kChannelGiven)) continue;
    const std::string key(c.name);
    dem::GivenChannel g{.channel = &c};
    if (c.components == 1) {
      const std::optional<Real> v = r.number(key);
      if (!v) continue;
      g.values[0] = *v;
    } else {
      const std::vector<Real> v = r.numbers(key, c.components);
      if (v.empty()) continue;
      std::copy(v.begin(), v.end(), g.values.begin());
    }
    d.given.push_back(g);
  }
}

void SceneReader::read_bonded_body(TableReader& r, const toml::table& table) {
  TableReader b(table, r.where() + ".shape", r, "shape");
  b.required_string("type");
  dem::BondedDef d;
  d.label = r.where();
  d.shape = read_shape(b, "shape");
  read_bonded_cut(b, d);
  b.finish();
  d.material = material_of(r);
  for (const char* key : {"name", "fixed", "motion"})
    if (r.has(key)) r.fail(key, "is not for a bonded assembly (its pieces move, each a body of its own)");
  d.position = r.vec3_or("position", Vec3{});
  d.rotation = r.rotation_or("rotation", Quat{});
  d.velocity = r.vec3_or("velocity", Vec3{});
  d.angular_velocity = r.vec3_or("angular_velocity", Vec3{});
  const std::vector<std::uint32_t> indices = building(r.table_node(), [&] { return builder_->add_bonded(d); });
  for (const std::uint32_t index : indices) body_lines_[index] = r.table_node().source().begin.line;
}

SceneReader::Region SceneReader::read_region(TableReader& r, bool flat) {
  const toml::table* t = r.table("region");
  if (!t) throw SceneError(r.where() + ": missing required key 'region'" + line_of(r.table_node()));
  TableReader region(*t, r.where() + ".region", r, "region");
  const std::string type = region.string_or("type", "box");
  Region g;
  if (type == "box") {
    std::tie(g.lo, g.hi) = read_box_region(region, *t, !flat);
    return g;
  }
  dem::RoundRegion round;
  if (type == "cylinder") {
    round.base = region.vec3_or("base", Vec3{});
    round.axis = region.vec3_or("axis", Vec3{0, 0, 1});
    if (!(length(round.axis) > 0)) region.fail("axis", "must not be zero");
    round.radius = region.positive("radius");
    if (flat) {
      round.height = region.number("height").value_or(-1);
      if (!(round.height >= 0)) region.fail("height", "must be >= 0 (0: a disc)");
    } else {
      round.height = region.positive("height");
    }
  } else if (type == "sphere") {
    round.kind = dem::RoundRegion::Kind::Ball;
    const std::optional<Vec3> centre = region.vec3("centre");
    if (!centre) throw SceneError(region.where() + ": a sphere region needs 'centre'" + line_of(*t));
    round.base = *centre;
    round.radius = region.positive("radius");
  } else {
    region.fail("type", "must be \"box\", \"cylinder\" or \"sphere\", not \"" + type + "\"");
  }
  region.finish();
  g.round = round;
  return g;
}

std::pair<Vec3, Vec3> SceneReader::read_box_region(TableReader& region, const toml::table& t, bool strict) {
  const Vec3 lo = region.vec3("min").value_or(Vec3{}), hi = region.vec3("max").value_or(Vec3{});
  if (!region.has("min") || !region.has("max"))
    throw SceneError(region.where() + ": needs 'min' and 'max'" + line_of(t));
  if (strict ? !(hi.x > lo.x && hi.y > lo.y && hi.z > lo.z) : !(hi.x >= lo.x && hi.y >= lo.y && hi.z >= lo.z))
    region.fail("max", strict ? "must exceed 'min' on every axis" : "must not be below 'min' on any axis");
  region.finish();
  return {lo, hi};
}

PolyhedronSpec SceneReader::read_polyhedron_spec(TableReader& s, const toml::table& t, bool sized_by_table) {
  s.required_string("type");
  PolyhedronSpec p;
  p.vertices = s.integer_or("vertices", 12);
  if (p.vertices < 4 || p.vertices > 10000) s.fail("vertices", "must be between 4 and 10000");
  if (const toml::node* n = s.find("size"); n && n->is_number()) {
    p.size_lo = p.size_hi = s.positive("size");
  } else {
    const std::vector<Real> range = s.numbers("size", 2);
    if (range.empty() && !sized_by_table) throw SceneError(s.where() + ": missing required key 'size'" + line_of(t));
    if (!range.empty()) {
      p.size_lo = range[0], p.size_hi = range[1];
      if (!(p.size_lo > 0 && p.size_hi >= p.size_lo)) s.fail("size", "must be [min, max] with 0 < min <= max");
    }
  }
  if (sized_by_table && p.size_hi > 0) s.fail("size", "is given by the sieve table 'sizes': remove it here");
  s.finish();
  return p;
}

bool SceneReader::is_random_polyhedron(const toml::table& t) {
  return t.get("type") && t.get("type")->value<std::string>() == std::optional<std::string>("random_polyhedron");
}

SceneReader::Mix SceneReader::read_mix(TableReader& r, std::int64_t count, std::mt19937_64& rng) {
  Mix mix;
  if (!r.has("sizes") && !r.has("shapes")) {  // one shape, equal variants (as before tables existed)
    const std::int64_t variants = r.integer_or("variants", std::min<std::int64_t>(count, 50));
    if (variants <= 0 || variants > std::min<std::int64_t>(count, kMaxVariants))
      r.fail("variants", "must be a positive integer up to the count and " + std::to_string(kMaxVariants));
    const toml::table* st = shape_table_at(r, "shape");
    if (!st) throw SceneError(r.where() + ": missing required key 'shape'" + line_of(r.table_node()));
    if (is_random_polyhedron(*st)) {
      TableReader s(*st, r.where() + ".shape", r, "shape");
      const PolyhedronSpec p = read_polyhedron_spec(s, *st, false);
      if (p.vertices * variants > kMaxGeneratorVertices)
        s.fail("vertices", "times the variants must stay under " + std::to_string(kMaxGeneratorVertices) +
                               " (memory for the shapes)");
      std::uniform_real_distribution<double> draw(p.size_lo, p.size_hi);
      for (std::int64_t k = 0; k < variants; ++k)
        mix.variants.push_back({random_polyhedron(static_cast<int>(p.vertices), draw(rng), rng), {}});
    } else {
      mix.variants.push_back(read_shape(r, "shape"));
    }
    return mix;
  }

  // Parts (a shape and its fraction), each in the size classes of the sieve table.
  struct Part {
    const toml::table* table;
    std::string where;
    Real fraction;
  };
  std::vector<Part> parts;
  if (const toml::node* n = r.find("shapes")) {
    const toml::array* a = n->as_array();
    if (!a || a->empty() || !a->is_array_of_tables())
      r.fail("shapes", "must be an array of { shape = SHAPE, fraction = f } tables");
    for (std::size_t k = 0; k < a->size(); ++k) {
      TableReader part(*(*a)[k].as_table(), r.where() + ".shapes[" + std::to_string(k) + "]", r, "shapes",
                       TableReader::Echo::Appended);
      const toml::table* shape = shape_table_at(part, "shape");
      if (!shape) throw SceneError(part.where() + ": missing required key 'shape'" + line_of(*(*a)[k].as_table()));
      const Real f = part.number("fraction").value_or(-1);
      if (!(f > 0)) part.fail("fraction", "must be > 0");
      part.finish();
      parts.push_back({shape, part.where() + ".shape", f});
    }
    if (r.has("shape")) r.fail("shape", "give either 'shape' or 'shapes', not both");
  } else {
    const toml::table* shape = shape_table_at(r, "shape");
    if (!shape) throw SceneError(r.where() + ": missing required key 'shape'" + line_of(r.table_node()));
    parts.push_back({shape, r.where() + ".shape", 1});
  }
  const std::string fractions = r.string_or("fractions", "number");
  if (fractions != "number" && fractions != "mass") r.fail("fractions", "must be \"number\" or \"mass\"");
  std::vector<SizeClass> classes;
  const std::string sieve_row = "[min_size, max_size, mass_fraction] (a sieve table)";
  if (r.has("sizes")) {
    Real total = 0;
    for (const std::vector<Real>& v : r.rows("sizes", 3, sieve_row)) {
      if (!(v[0] > 0 && v[1] >= v[0])) r.fail("sizes", "sizes must be finite with 0 < min_size <= max_size");
      if (!(v[2] >= 0)) r.fail("sizes", "mass fractions must be finite and >= 0");
      classes.push_back({v[0], v[1], v[2]});
      total += v[2];
    }
    if (!(std::fabs(total - 1) <= kMassFractionSumTol))
      r.fail("sizes", "the mass fractions add up to " + std::to_string(total) + ", not 1");
  }
  const bool sized = !classes.empty();
  const std::size_t class_count = sized ? classes.size() : 1;
  const std::int64_t per_group = r.integer_or("variants", sized ? 10 : 1);
  if (per_group <= 0 || per_group * static_cast<std::int64_t>(parts.size() * class_count) > kMaxVariants)
    r.fail("variants", "must be a positive integer (variants per shape and size class), all of them up to " +
                           std::to_string(kMaxVariants));
  std::vector<MixPart> mix_parts;
  for (const Part& part : parts) {
    TableReader s(*part.table, part.where);
    MixPart m;
    m.where = part.where, m.fraction = part.fraction;
    if (is_random_polyhedron(*part.table)) {
      m.polyhedron = read_polyhedron_spec(s, *part.table, sized);
      if (m.polyhedron->vertices * per_group * static_cast<std::int64_t>(class_count) > kMaxGeneratorVertices)
        s.fail("vertices", "times the variants must stay under " + std::to_string(kMaxGeneratorVertices));
    } else {
      m.base = read_shape_table(*part.table, part.where);
      if (m.base.shell)
        throw SceneError(part.where + ": a thin shell is a [[body]] of its own (generators and inflows do not make them)" +
                         line_of(*part.table));
      m.base_size = 2 * bounding_radius(m.base.shape);
      for (const PlacedShape& p : m.base.parts)  // a compound: of the sphere about its frame holding its parts
        m.base_size = std::fmax(m.base_size, 2 * (length(p.pose.translation) + bounding_radius(p.shape)));
      if (m.base.surface)  // a surface grain: of the sphere about its frame holding its vertices
        for (const Vec3& v : m.base.surface->vertices) m.base_size = std::fmax(m.base_size, 2 * length(v));
      for (const dem::PlacedSurface& p : m.base.surface_parts)
        for (const Vec3& v : p.surface->vertices) m.base_size = std::fmax(m.base_size, 2 * length(apply(p.pose, v)));
      if (!(m.base_size > 0)) throw SceneError(part.where + ": a shape without size cannot be sized by the table");
    }
    mix_parts.push_back(std::move(m));
  }
  SampledMix sampled = sample_mix(mix_parts, classes, per_group, fractions == "mass", rng);
  mix.variants = std::move(sampled.variants);
  mix.weights = std::move(sampled.weights);
  return mix;
}

void SceneReader::read_generator(TableReader& r) {
  const std::int64_t count = r.integer("count").value_or(-1);
  building(r, [&] { dem::check_fill_count(count); });  // before anything is drawn
  dem::RegionFill fill;
  fill.label = r.where();
  fill.count = static_cast<std::size_t>(count);
  fill.material = material_of(r);
  const Region region = read_region(r, false);
  fill.lo = region.lo, fill.hi = region.hi, fill.round = region.round;
  fill.velocity = r.vec3_or("velocity", Vec3{});
  fill.fixed = r.boolean("fixed", false);
  std::mt19937_64 rng(dem::derived_seed(scene_.seed, generator_count_++));
  const toml::table* bonded = bonded_table(r);
  Mix mix = bonded ? read_bonded_mix(r, *bonded, fill) : read_mix(r, count, rng);
  fill.variants = std::move(mix.variants);
  fill.weights = std::move(mix.weights);
  const std::vector<std::uint32_t> placed = building(*r.table("region"), [&] { return builder_->fill_region(fill, rng); });
  warn_of_bodies_outside_containers(r.where(), placed);
}

const toml::table* SceneReader::bonded_table(TableReader& r) {
  const toml::node* n = r.find("shape");
  if (!n || !n->is_table()) return nullptr;
  const toml::table& t = *n->as_table();
  return t.get("type") && t.get("type")->value<std::string>() == std::optional<std::string>("bonded") ? &t : nullptr;
}

SceneReader::Mix SceneReader::read_bonded_mix(TableReader& r, const toml::table& table, dem::RegionFill& fill) {
  for (const char* key : {"shapes", "sizes", "variants", "fractions"})
    if (r.has(key))
      r.fail(key, "is not for a generator of bonded assemblies (one shape, each assembly cut anew from its seed)");
  if (fill.fixed) r.fail("fixed", "bonded assemblies move: they cannot be fixed");
  TableReader b(table, r.where() + ".shape", r, "shape");
  b.required_string("type");
  Mix mix;
  mix.variants.push_back(read_shape(b, "shape"));
  dem::BondedDef cut;
  read_bonded_cut(b, cut);
  b.finish();
  fill.pieces = cut.pieces, fill.pieces_seed = cut.seed, fill.relaxations = cut.relaxations;
  return mix;
}

void SceneReader::read_bonded_cut(TableReader& b, dem::BondedDef& d) {
  const std::int64_t pieces = b.integer("pieces").value_or(0);
  if (pieces < 2 || pieces > dem::kMaxBondedPieces)
    b.fail("pieces", "must be given, between 2 and " + std::to_string(dem::kMaxBondedPieces));
  d.pieces = static_cast<std::uint32_t>(pieces);
  const std::int64_t seed = b.integer_or("seed", 1);
  if (seed < 0) b.fail("seed", "must be >= 0");
  d.seed = static_cast<std::uint64_t>(seed);
  const std::int64_t relaxations = b.integer_or("relaxations", 3);
  if (relaxations < 0 || relaxations > 100) b.fail("relaxations", "must be between 0 and 100");
  d.relaxations = static_cast<int>(relaxations);
}

void SceneReader::read_inflow(TableReader& r) {
  dem::InflowDef d;
  d.label = r.where();
  d.material = material_of(r);
  const Region region = read_region(r, true);
  d.lo = region.lo, d.hi = region.hi, d.round = region.round;
  d.velocity = r.vec3_or("velocity", Vec3{});
  const std::optional<Real> rate = r.number("rate"), mass_rate = r.number("mass_rate");
  if (rate.has_value() == mass_rate.has_value())
    throw SceneError(r.where() + ": give one of 'rate' (bodies per second) and 'mass_rate' (kg per second)" +
                     line_of(r.table_node()));
  if (rate && !(*rate > 0)) r.fail("rate", "must be > 0");
  if (mass_rate && !(*mass_rate > 0)) r.fail("mass_rate", "must be > 0");
  d.rate = rate.value_or(0);
  d.mass_rate = mass_rate.value_or(0);
  d.start = r.number_or("start", 0);
  if (!(d.start >= 0)) r.fail("start", "must be >= 0");
  d.stop = r.number_or("stop", scene_.duration);
  if (!(d.stop > d.start)) r.fail("stop", "must come after the start");
  const std::int64_t count = r.integer_or("count", 0);  // 0: no limit
  if (count < 0 || count > static_cast<std::int64_t>(dem::kMaxInflowBodies))
    r.fail("count", "must be a positive integer up to " + std::to_string(dem::kMaxInflowBodies));
  d.count = static_cast<std::uint64_t>(count);
  d.seed = dem::derived_seed(scene_.seed, kInflowStreams + inflow_count_);
  std::mt19937_64 rng(d.seed);
  Mix mix = read_mix(r, count > 0 ? count : 50, rng);
  d.variants = std::move(mix.variants);
  d.weights = std::move(mix.weights);
  building(r.table_node(), [&] { return builder_->add_inflow(d); });
  ++inflow_count_;
}

}  // namespace gjkdem::io::detail
