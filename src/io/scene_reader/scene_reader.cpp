// The scene reader's whole (scene_reader.hpp): the file's tables in order,
// the settings (simulation, output, contact) and the materials; the entry
// points of scene.hpp.
#include "scene_reader/scene_reader.hpp"

namespace gjkdem::io::detail {

SceneShape SceneReader::one_shape(const toml::table& t, const std::string& where, std::uint64_t seed) {
  SceneShape out;
  if (is_random_polyhedron(t)) {
    TableReader r(t, where);
    const PolyhedronSpec p = read_polyhedron_spec(r, t, false);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> draw(p.size_lo, p.size_hi);
    out.shape = {random_polyhedron(static_cast<int>(p.vertices), draw(rng), rng), {}};
  } else {
    out.shape = read_shape_table(t, where);
  }
  out.warnings = std::move(scene_.warnings);
  return out;
}

Scene SceneReader::build(const toml::table& root) {
  TableReader top(root, source_);
  // The sections read below: a misspelt one ([[plane]]) was told only after
  // every body was cut and placed, minutes on a big scene.
  static constexpr std::string_view kSections[] = {"simulation", "output", "contact", "material", "shapes",
                                                   "wall",       "body",   "generator", "inflow"};
  top.refuse_keys_but(kSections);
  read_simulation(top);
  read_output(top);
  read_contact(top);
  builder_.emplace(settings_);
  builder_->set_progress(progress_);
  if (accept_overlaps_) builder_->accept_initial_overlaps();
  for_each_table(top, "material", [&](TableReader& r) { read_material(r); });
  read_named_shapes(top);
  for_each_table(top, "wall", [&](TableReader& r) { read_wall(r); });
  for_each_table(top, "body", [&](TableReader& r) { read_body(r); });
  for_each_table(top, "generator", [&](TableReader& r) { read_generator(r); });
  for_each_table(top, "inflow", [&](TableReader& r) { read_inflow(r); });
  top.finish();
  if (builder_->moving_count() == 0 && inflow_count_ == 0)
    throw SceneError(source_ + ": the scene has no moving body (add a [[body]], a [[generator]] or an [[inflow]])");
  try {
    scene_.world = builder_->build();
  } catch (const dem::BuildError& e) {
    std::string lines;  // of the bodies at fault, when the scene gave them
    for (const std::uint32_t b : e.bodies)
      if (const auto it = body_lines_.find(b); it != body_lines_.end())
        lines += (lines.empty() ? " (line " : ", line ") + std::to_string(it->second);
    throw SceneError(source_ + ": " + e.what() + (lines.empty() ? "" : lines + ")"));
  }
  if (scene_.dt_auto) scene_.dt = dem::critical_time_step(scene_.world);
  Json resolved = top.take_echo();
  resolved["simulation"]["dt"] = scene_.dt;  // "auto" resolved
  resolved["simulation"]["dt_auto"] = scene_.dt_auto;
  scene_.resolved_json = resolved.dump(2);
  return std::move(scene_);
}

const toml::table* SceneReader::sub_table(TableReader& top, const std::string& key) {
  const toml::node* n = top.find(key);
  if (!n) return nullptr;
  if (!n->is_table()) top.fail(key, "must be a table: write [" + key + "]");
  return n->as_table();
}

void SceneReader::read_simulation(TableReader& top) {
  const toml::table* t = sub_table(top, "simulation");
  if (!t) throw SceneError(source_ + ": missing the [simulation] table (it needs 'duration')");
  TableReader r(*t, "simulation", top, "simulation");
  scene_.duration = r.positive("duration");
  if (const toml::node* n = r.find("dt")) {
    if (n->is_string()) {
      if (n->value<std::string>().value() != "auto") r.fail("dt", "must be a number of seconds or \"auto\"");
    } else {
      scene_.dt_auto = false;
      scene_.dt = r.positive("dt");
    }
  }
  settings_.gravity = r.vec3_or("gravity", dem::WorldSettings{}.gravity);
  const std::int64_t threads = r.integer_or("threads", 0);  // a scene's default: every core
  settings_.threads = clamped_int(threads);
  const std::string overlaps = r.string_or("initial_overlaps", "refuse");
  if (overlaps != "refuse" && overlaps != "accept")
    r.fail("initial_overlaps", "must be \"refuse\" or \"accept\", not \"" + overlaps + "\"");
  accept_overlaps_ = overlaps == "accept";
  const std::string guards = r.string_or("guards", "stop");
  if (guards == "stop") scene_.guards.action = dem::GuardAction::Stop;
  else if (guards == "warn") scene_.guards.action = dem::GuardAction::Warn;
  else if (guards == "off") scene_.guards.action = dem::GuardAction::Off;
  else r.fail("guards", "must be \"stop\", \"warn\" or \"off\", not \"" + guards + "\"");
  const std::int64_t seed = r.integer_or("seed", static_cast<std::int64_t>(scene_.seed));
  if (seed < 0) r.fail("seed", "must be >= 0");
  scene_.seed = static_cast<std::uint64_t>(seed);
  if (const toml::table* periodic_table = r.table("periodic")) {
    TableReader p(*periodic_table, r.where() + ".periodic", r, "periodic");
    const char* names[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      const std::vector<Real> range = p.numbers(names[a], 2);
      if (range.empty()) continue;
      settings_.periodic.axes[a] = true;
      settings_.periodic.lo[a] = range[0];
      settings_.periodic.hi[a] = range[1];
    }
    if (!settings_.periodic.active()) r.fail("periodic", "needs at least one axis, e.g. { x = [0.0, 0.1] }");
    // How the cell deforms: per component a strain rate or a target stress.
    dem::CellControl& control = settings_.cell_control;
    const auto components = [&](const char* key, dem::CellMode mode, const char* example) {
      const toml::table* given_table = p.table(key);
      if (!given_table) return;
      TableReader q(*given_table, p.where() + "." + key, p, key);
      bool given = false;
      for (int k = 0; k < 6; ++k) {
        const char* name = dem::kCellComponents[k];
        const std::optional<Real> v = q.number(name);
        if (!v) continue;
        if (control.mode[k] != dem::CellMode::Fixed)
          q.fail(name, "a component takes either a strain rate or a stress, not both");
        control.mode[k] = mode;
        control.value[k] = *v;
        given = true;
      }
      q.finish();
      if (!given) p.fail(key, std::string("needs at least one component, e.g. ") + example);
    };
    components("strain_rate", dem::CellMode::StrainRate, "{ z = -0.1 } or { xz = 1.0 }");
    components("stress", dem::CellMode::Stress, "{ x = 1.0e4, y = 1.0e4, z = 1.0e4 }");
    if (const std::optional<Real> rate = p.number("max_strain_rate")) control.max_strain_rate = *rate;
    p.finish();
  }
  r.finish();
  building(r, [&] { dem::check_settings(settings_); });
}

void SceneReader::read_output(TableReader& top) {
  const toml::table none, *t = sub_table(top, "output");  // absent: all its defaults (Scene's)
  TableReader r(t ? *t : none, "output", top, "output");
  scene_.output_dir = r.string_or("dir", scene_.output_dir);
  if (scene_.output_dir.empty()) r.fail("dir", "must not be empty");
  scene_.output_every = r.positive("every", scene_.duration / 100);
  scene_.overwrite = r.boolean("overwrite", scene_.overwrite);
  const std::int64_t every = r.integer_or("checkpoint_every", scene_.checkpoint_every);
  if (every < 0) r.fail("checkpoint_every", "must be >= 0 (0: no checkpoints)");
  scene_.checkpoint_every = static_cast<int>(every);
  scene_.write_frames = r.boolean("frames", scene_.write_frames);
  scene_.write_view = r.boolean("view", scene_.write_view);
  r.finish();
}

void SceneReader::read_contact(TableReader& top) {
  dem::WorldSettings& w = settings_;
  const toml::table none, *t = sub_table(top, "contact");  // absent: all its defaults
  TableReader r(t ? *t : none, "contact", top, "contact");
  const std::string model = r.string_or("model", dem::name_of(w.model));
  if (const auto m = dem::contact_model_named(model)) w.model = *m;
  else r.fail("model", std::string("must be ") + dem::kContactModelNames + ", not \"" + model + "\"");
  w.volume_stiffness = r.number_or("volume_stiffness", w.volume_stiffness);
  const std::string form = r.string_or("volume_form", dem::name_of(w.volume_form));
  if (const auto f = dem::volume_form_named(form)) w.volume_form = *f;
  else r.fail("volume_form", std::string("must be ") + dem::kVolumeFormNames + ", not \"" + form + "\"");
  w.linear_stiffness = r.number_or("linear_stiffness", w.linear_stiffness);
  w.rocking_resistance = r.boolean("rocking_resistance", w.rocking_resistance);
  w.tessellation = clamped_int(r.integer_or("tessellation", w.tessellation));
  building(r, [&] { dem::check_contact_settings(w); });
  r.finish();
}

void SceneReader::read_material(TableReader& r) {
  dem::Material m;  // its defaults are the scene's
  m.name = r.required_string("name");
  m.density = r.required_number("density");
  m.youngs_modulus = r.required_number("youngs_modulus");
  for (auto [key, value] : {std::pair{"poisson_ratio", &m.poisson_ratio}, {"restitution", &m.restitution},
                            {"friction", &m.friction}, {"rolling_friction", &m.rolling_friction},
                            {"rolling_damping", &m.rolling_damping}})
    *value = r.number_or(key, *value);
  dem::Strength& st = m.strength;  // breakage (docs/breakage.md)
  for (auto [key, value] : {std::pair{"strength", &st.mean}, {"weibull_modulus", &st.weibull_modulus},
                            {"strength_size", &st.reference_size}, {"unbreakable_below", &st.smallest}})
    *value = r.number_or(key, *value);
  const std::int64_t strength_seed = r.integer_or("strength_seed", static_cast<std::int64_t>(st.seed));
  if (strength_seed < 0) r.fail("strength_seed", "must be >= 0");
  st.seed = static_cast<std::uint64_t>(strength_seed);
  dem::Glue& g = m.glue;  // bonded assemblies (docs/breakage.md)
  for (auto [key, value] : {std::pair{"bond_tensile_strength", &g.tensile_strength},
                            {"bond_shear_strength", &g.shear_strength}, {"bond_moment_strength", &g.moment_strength},
                            {"bond_normal_stiffness", &g.normal_stiffness},
                            {"bond_shear_stiffness", &g.shear_stiffness}, {"bond_damping", &g.damping}})
    *value = r.number_or(key, *value);
  building(r, [&] { return builder_->add_material(m); });
}

std::uint32_t SceneReader::material_of(TableReader& r) {
  const std::string name = r.required_string("material");
  const std::optional<std::uint32_t> m = builder_->find_material(name);
  if (!m) r.fail("material", "no [[material]] is named '" + name + "'");
  return *m;
}

}  // namespace gjkdem::io::detail

namespace gjkdem::io {

Scene load_scene(std::string_view toml_text, const std::string& source, const std::filesystem::path& base_dir,
                 const dem::BuildProgress& progress) {
  detail::check_key_depth(toml_text, source);
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    throw SceneError(source + ": " + std::string(e.description()) + " (line " +
                     std::to_string(e.source().begin.line) + ")");
  }
  return detail::SceneReader(source, base_dir, progress).build(root);
}

SceneShape read_scene_shape(std::string_view toml_inline_table, const std::filesystem::path& base_dir,
                            const std::string& where, std::uint64_t seed) {
  const std::string text = "shape = " + std::string(toml_inline_table);
  detail::check_key_depth(text, where);
  toml::table root;
  try {
    root = toml::parse(text, where);
  } catch (const toml::parse_error& e) {
    throw SceneError(where + ": " + std::string(e.description()));
  }
  const toml::table* t = root["shape"].as_table();
  if (!t) throw SceneError(where + ": a SHAPE is a table");
  return detail::SceneReader(where, base_dir).one_shape(*t, where, seed);
}

std::string read_text_file(const std::filesystem::path& file) {
  std::optional<std::string> text = read_file(file);
  if (!text) throw SceneError("cannot read " + file.string());
  return std::move(*text);
}

Scene load_scene_file(const std::filesystem::path& file) {
  return load_scene(read_text_file(file), file.string(), file.has_parent_path() ? file.parent_path() : ".");
}

}  // namespace gjkdem::io
