#include "gjkdem/io/view_format.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "gjkdem/io/run_output.hpp"

namespace gjkdem::io {

namespace {

static_assert(std::endian::native == std::endian::little, "the view format is written in the machine's byte order");

constexpr char kShapesMagic[8] = {'G', 'J', 'K', 'S', 'H', 'A', 'P', 'E'};
constexpr char kFrameMagic[8] = {'G', 'J', 'K', 'F', 'R', 'A', 'M', 'E'};

template <class T>
void put(std::string& out, const T& value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

template <class T>
void put_array(std::string& out, const std::vector<T>& values) {
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

void pad4(std::string& out) { out.append((4 - out.size() % 4) % 4, '\0'); }

// Every number a frame holds as a float: a double beyond float's range (a
// position within the supported 1e100 m, a force) is written as float's
// largest, with its sign, never as inf, so that the frames stay readable.
float frame_float(Real v) {
  constexpr Real kLargest = std::numeric_limits<float>::max();
  return static_cast<float>(std::clamp(v, -kLargest, kLargest));
}

void put_vec(std::vector<float>& out, const Vec3& v) {
  out.push_back(frame_float(v.x)), out.push_back(frame_float(v.y)), out.push_back(frame_float(v.z));
}

/// Reads fields in order, refusing to run past the end.
class Reader {
 public:
  Reader(const std::string& bytes, const char* what) : bytes_(bytes), what_(what) {}
  template <class T>
  T get() {
    T value;
    take(&value, sizeof value);
    return value;
  }
  template <class T>
  void get_array(std::vector<T>& out, std::uint64_t count) {
    if (count > (bytes_.size() - at_) / sizeof(T)) fail("is cut short: shorter than its counts say");
    out.resize(count);
    take(out.data(), count * sizeof(T));
  }
  void skip_pad4() {
    const std::size_t pad = (4 - at_ % 4) % 4;
    if (pad > bytes_.size() - at_) fail("is cut short");
    for (std::size_t k = 0; k < pad; ++k)
      if (bytes_[at_ + k] != 0) fail("has padding that is not zero");
    at_ += pad;
  }
  void expect_magic(const char (&magic)[8]) {
    char m[8];
    take(m, 8);
    if (std::memcmp(m, magic, 8) != 0) fail("is not a gjkdem view file (wrong magic)");
    version_ = get<std::uint32_t>();
    if (version_ < kOldestViewVersion || version_ > kViewVersion)
      fail("has view format version " + std::to_string(version_) + "; this gjkdem reads versions " +
           std::to_string(kOldestViewVersion) + " to " + std::to_string(kViewVersion));
  }
  std::uint32_t version() const noexcept { return version_; }
  void expect_end() const {
    if (at_ != bytes_.size()) fail("has " + std::to_string(bytes_.size() - at_) + " bytes past its end");
  }
  [[noreturn]] void fail(const std::string& why) const { throw ViewFormatError(std::string(what_) + " " + why); }

 private:
  void take(void* out, std::size_t n) {
    if (n > bytes_.size() - at_) fail("is cut short");
    std::memcpy(out, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::string& bytes_;
  const char* what_;
  std::size_t at_ = 0;
  std::uint32_t version_ = 0;
};

ViewMesh view_mesh(const dem::ShapeTemplate& t) {
  const DisplayMesh polygons = display_mesh(t);
  // Display meshes are in the template's frame; the view's are in the body's
  // (principal) frame, so that a body's pose places them directly.
  const Transform body_from_shape = dem::shape_pose(t, dem::Body{});
  ViewMesh m;
  for (const Vec3& v : polygons.vertices) put_vec(m.vertices, apply(body_from_shape, v));
  for (std::size_t k = 0; k + 1 < polygons.polygon_begin.size(); ++k)
    for (std::uint32_t i = polygons.polygon_begin[k] + 1; i + 1 < polygons.polygon_begin[k + 1]; ++i)
      m.triangles.insert(m.triangles.end(),
                         {polygons.indices[polygons.polygon_begin[k]], polygons.indices[i], polygons.indices[i + 1]});
  return m;
}

}  // namespace

ViewShapes view_shapes(const dem::World& w) {
  ViewShapes s;
  for (const dem::ShapeTemplate& t : w.templates) s.templates.push_back(view_mesh(t));
  for (const dem::PlaneWall& p : w.planes) s.plane_ids.push_back(static_cast<std::uint32_t>(p.id));
  return s;
}

ViewFrame view_frame(const dem::World& w, std::uint64_t step) {
  ViewFrame f;
  f.time = w.time;
  f.step = step;
  const std::size_t n = w.bodies.size();
  f.positions.reserve(3 * n), f.orientations.reserve(4 * n), f.velocities.reserve(3 * n);
  f.angular_velocities.reserve(3 * n), f.templates.reserve(n), f.ids.reserve(n), f.flags.reserve(n);
  for (const dem::Body& b : w.bodies) {
    put_vec(f.positions, b.position);
    for (const Real c : {b.orientation.w, b.orientation.x, b.orientation.y, b.orientation.z})
      f.orientations.push_back(frame_float(c));
    put_vec(f.velocities, b.velocity);
    put_vec(f.angular_velocities, dem::angular_velocity_of(w, b));
    f.templates.push_back(b.shape);
    f.ids.push_back(static_cast<std::uint32_t>(b.id));
    f.flags.push_back(static_cast<std::uint8_t>((b.fixed ? kViewFixed : 0) | (b.motion ? kViewDriven : 0)));
  }
  for (const dem::StepContact& c : w.results.contacts) {
    if (!c.active) continue;
    f.contact_a.push_back(c.a_is_plane ? kViewPlaneSide + c.a : c.a);
    f.contact_b.push_back(c.b);
    put_vec(f.contact_points, c.geometry.point);
    put_vec(f.contact_normals, c.geometry.normal);
    put_vec(f.contact_forces, c.force);
  }
  for (const dem::PlaneWall& p : w.planes) put_vec(f.plane_points, p.point), put_vec(f.plane_normals, p.normal);
  for (int a = 0; a < 3; ++a) f.cell_axes |= w.cell.now.axes[a] ? 1u << a : 0u;
  const Vec3 cell[3] = {w.cell.now.lo, w.cell.now.hi, w.cell.now.tilt};
  for (int k = 0; k < 9; ++k) f.cell[k] = f.cell_axes ? frame_float(cell[k / 3][k % 3]) : 0.0f;
  for (const dem::Bond& bond : w.bonds) {
    const std::size_t a = dem::index_of_body(w.bodies, bond.a), b = dem::index_of_body(w.bodies, bond.b);
    if (a >= w.bodies.size() || b >= w.bodies.size()) continue;
    const dem::Body &ba = w.bodies[a], &bb = w.bodies[b];
    f.bond_first.push_back(static_cast<std::uint32_t>(a)), f.bond_second.push_back(static_cast<std::uint32_t>(b));
    put_vec(f.bond_points, (ba.position + rotate(ba.orientation, bond.point_a) + bb.position +
                            rotate(bb.orientation, bond.point_b)) * 0.5);
    f.bond_intact.push_back(bond.intact);
  }
  Real values[dem::kMaxChannelComponents];
  for (const dem::BodyChannel& ch : dem::kBodyChannels) {
    if (!(ch.use & dem::kChannelFramed) || !ch.in_outputs_of(w)) continue;
    ViewChannel& c = f.channels.emplace_back(ViewChannel{std::string(ch.name), std::string(ch.unit), ch.components, {}});
    c.values.reserve(ch.components * n);
    for (const dem::Body& b : w.bodies) {
      ch.read(w, b, values);
      for (std::uint32_t k = 0; k < ch.components; ++k) c.values.push_back(frame_float(values[k]));
    }
  }
  return f;
}

std::string encode(const ViewShapes& s) {
  std::string out(kShapesMagic, 8);
  put(out, kViewVersion);
  put(out, static_cast<std::uint32_t>(s.templates.size()));
  put(out, static_cast<std::uint32_t>(s.plane_ids.size()));
  put(out, std::uint32_t{0});
  for (const ViewMesh& m : s.templates) {
    put(out, static_cast<std::uint32_t>(m.vertices.size() / 3));
    put(out, static_cast<std::uint32_t>(m.triangles.size() / 3));
    put_array(out, m.vertices);
    put_array(out, m.triangles);
  }
  put_array(out, s.plane_ids);
  return out;
}

std::string encode(const ViewFrame& f) {
  const std::size_t n = f.body_count(), m = f.contact_count();
  std::string out(kFrameMagic, 8);
  out.reserve(40 + 61 * n + 4 + 44 * m + 24 * (f.plane_points.size() / 3) + 40);
  put(out, kViewVersion);
  put(out, static_cast<std::uint32_t>(n));
  put(out, static_cast<std::uint32_t>(m));
  put(out, static_cast<std::uint32_t>(f.plane_points.size() / 3));
  put(out, f.time);
  put(out, f.step);
  put_array(out, f.positions), put_array(out, f.orientations), put_array(out, f.velocities);
  put_array(out, f.angular_velocities), put_array(out, f.templates), put_array(out, f.ids), put_array(out, f.flags);
  pad4(out);
  put_array(out, f.contact_a), put_array(out, f.contact_b);
  put_array(out, f.contact_points), put_array(out, f.contact_normals), put_array(out, f.contact_forces);
  put_array(out, f.plane_points), put_array(out, f.plane_normals);
  put(out, f.cell_axes);
  for (const float v : f.cell) put(out, v);
  put(out, static_cast<std::uint32_t>(f.bond_count()));
  put_array(out, f.bond_first), put_array(out, f.bond_second), put_array(out, f.bond_points);
  put_array(out, f.bond_intact);
  pad4(out);
  put(out, static_cast<std::uint32_t>(f.channels.size()));
  for (const ViewChannel& c : f.channels) {
    put(out, c.components);
    put(out, static_cast<std::uint32_t>(c.name.size()));
    put(out, static_cast<std::uint32_t>(c.unit.size()));
    out += c.name;
    out += c.unit;
    pad4(out);
    put_array(out, c.values);
  }
  return out;
}

ViewShapes decode_view_shapes(const std::string& bytes) {
  Reader r(bytes, "shapes.bin");
  r.expect_magic(kShapesMagic);
  const auto templates = r.get<std::uint32_t>(), planes = r.get<std::uint32_t>();
  r.get<std::uint32_t>();
  ViewShapes s;
  for (std::uint32_t t = 0; t < templates; ++t) {
    ViewMesh m;
    const auto vertices = r.get<std::uint32_t>(), triangles = r.get<std::uint32_t>();
    r.get_array(m.vertices, 3ull * vertices);
    r.get_array(m.triangles, 3ull * triangles);
    for (const std::uint32_t i : m.triangles)
      if (i >= vertices) r.fail("has a triangle of template " + std::to_string(t) + " naming a vertex it does not have");
    s.templates.push_back(std::move(m));
  }
  r.get_array(s.plane_ids, planes);
  r.expect_end();
  return s;
}

ViewFrame decode_view_frame(const std::string& bytes) {
  Reader r(bytes, "frame");
  r.expect_magic(kFrameMagic);
  const std::uint64_t n = r.get<std::uint32_t>(), m = r.get<std::uint32_t>(), planes = r.get<std::uint32_t>();
  ViewFrame f;
  f.time = r.get<double>();
  f.step = r.get<std::uint64_t>();
  r.get_array(f.positions, 3 * n), r.get_array(f.orientations, 4 * n), r.get_array(f.velocities, 3 * n);
  r.get_array(f.angular_velocities, 3 * n), r.get_array(f.templates, n), r.get_array(f.ids, n);
  r.get_array(f.flags, n);
  r.skip_pad4();
  r.get_array(f.contact_a, m), r.get_array(f.contact_b, m);
  r.get_array(f.contact_points, 3 * m), r.get_array(f.contact_normals, 3 * m), r.get_array(f.contact_forces, 3 * m);
  r.get_array(f.plane_points, 3 * planes), r.get_array(f.plane_normals, 3 * planes);
  f.cell_axes = r.get<std::uint32_t>();
  for (float& v : f.cell) v = r.get<float>();
  if (r.version() >= 3) {
    const std::uint64_t k = r.get<std::uint32_t>();
    r.get_array(f.bond_first, k), r.get_array(f.bond_second, k), r.get_array(f.bond_points, 3 * k);
    r.get_array(f.bond_intact, k);
    for (std::uint64_t b = 0; b < k; ++b)
      if (f.bond_first[b] >= n || f.bond_second[b] >= n || f.bond_intact[b] > 1)
        r.fail("has bond " + std::to_string(b) + " naming a body it does not have, or a state it cannot have");
  }
  if (r.version() >= 4) {
    r.skip_pad4();
    const std::uint32_t channels = r.get<std::uint32_t>();
    for (std::uint32_t k = 0; k < channels; ++k) {
      ViewChannel c;
      c.components = r.get<std::uint32_t>();
      const std::uint32_t name_bytes = r.get<std::uint32_t>(), unit_bytes = r.get<std::uint32_t>();
      if (c.components < 1 || c.components > dem::kMaxChannelComponents || name_bytes < 1 ||
          name_bytes > dem::kMaxChannelNameBytes || unit_bytes > dem::kMaxChannelNameBytes)
        r.fail("has channel " + std::to_string(k) + " with a size, a name or a unit length it cannot have");
      std::vector<char> text;
      r.get_array(text, name_bytes + unit_bytes);
      c.name.assign(text.begin(), text.begin() + name_bytes);
      c.unit.assign(text.begin() + name_bytes, text.end());
      if (!dem::channel_name_ok(c.name))
        r.fail("has channel " + std::to_string(k) + " whose name is not lower case letters, digits and _");
      if (!dem::channel_unit_ok(c.unit)) r.fail("has channel '" + c.name + "' whose unit is not printable ASCII");
      for (const ViewChannel& before : f.channels)
        if (before.name == c.name) r.fail("has the channel '" + c.name + "' twice");
      r.skip_pad4();
      r.get_array(c.values, c.components * n);
      f.channels.push_back(std::move(c));
    }
  }
  r.expect_end();
  if (f.cell_axes > 7) r.fail("has periodic axes it cannot have");
  for (std::uint64_t k = 0; k < m; ++k) {
    const std::uint32_t a = f.contact_a[k];
    if (f.contact_b[k] >= n || (a & kViewPlaneSide ? a - kViewPlaneSide >= planes : a >= n))
      r.fail("has contact " + std::to_string(k) + " naming a body or plane it does not have");
  }
  return f;
}

std::filesystem::path view_shapes_file(const std::filesystem::path& view_dir) { return view_dir / "shapes.bin"; }

std::filesystem::path view_frame_file(const std::filesystem::path& view_dir, std::uint64_t frame) {
  char name[40];
  std::snprintf(name, sizeof name, "frame_%06llu.bin", static_cast<unsigned long long>(frame));
  return view_dir / name;
}

std::filesystem::path view_index_file(const std::filesystem::path& view_dir) { return view_dir / "index.csv"; }

void require_view_frames(const std::filesystem::path& run_dir) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(view_index_file(run_dir / "view"), ec))
    throw ViewFormatError(run_dir.string() + " holds no view frames (view/index.csv): it is not a run folder, or its "
                          "scene set output.view = false");
}

std::string view_index_header() { return "frame,time,step,bodies,contacts\n"; }

std::string view_index_row(const ViewIndexRow& row) {
  std::string line = std::to_string(row.frame);
  line += ',';
  append_number(line, row.time);
  for (const std::uint64_t n : {row.step, row.bodies, row.contacts}) line.append(",").append(std::to_string(n));
  return line + "\n";
}

namespace {

std::string bytes_of(const std::filesystem::path& file) {
  std::optional<std::string> bytes = read_file(file);
  if (!bytes) throw ViewFormatError("cannot read " + file.string());
  return std::move(*bytes);
}

}  // namespace

std::vector<ViewIndexRow> read_view_index(const std::filesystem::path& file) {
  std::string text = bytes_of(file);
  // A row is complete with its newline: a last line without one is still
  // being written (a run going on) and is left for the next read.
  text.resize(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line + "\n" != view_index_header())
    throw ViewFormatError(file.string() + " does not start with the view index header");
  std::vector<ViewIndexRow> rows;
  while (std::getline(in, line)) {
    ViewIndexRow r;
    unsigned long long frame, step, bodies, contacts;
    int used = 0;
    if (std::sscanf(line.c_str(), "%llu,%lf,%llu,%llu,%llu%n", &frame, &r.time, &step, &bodies, &contacts, &used) != 5 ||
        static_cast<std::size_t>(used) != line.size())
      throw ViewFormatError(file.string() + " line " + std::to_string(rows.size() + 2) + " is not a view index row");
    r.frame = frame, r.step = step, r.bodies = bodies, r.contacts = contacts;
    rows.push_back(r);
  }
  return rows;
}

ViewShapes read_view_shapes(const std::filesystem::path& file) {
  try {
    return decode_view_shapes(bytes_of(file));
  } catch (const ViewFormatError& e) {
    throw ViewFormatError(file.string() + ": " + e.what());
  }
}

ViewFrame read_view_frame(const std::filesystem::path& file) {
  try {
    return decode_view_frame(bytes_of(file));
  } catch (const ViewFormatError& e) {
    throw ViewFormatError(file.string() + ": " + e.what());
  }
}

}  // namespace gjkdem::io
