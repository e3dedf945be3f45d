#include "gjkdem/io/run_output.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cstring>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <sstream>

#include "gjkdem/dem/body_channels.hpp"
#include "gjkdem/shape/polytope.hpp"
#include "gjkdem/shape/tessellate.hpp"

namespace gjkdem::io {
namespace {

constexpr int kDisplayDirections = 64;

// Legacy VTK binary is big-endian.
template <class T>
void put_big_endian(std::string& out, T value) {
  auto bits = std::bit_cast<std::array<char, sizeof(T)>>(value);
  if constexpr (std::endian::native == std::endian::little) std::reverse(bits.begin(), bits.end());
  out.append(bits.data(), bits.size());
}

void polytope_mesh(const PolytopeData& d, DisplayMesh& m) {
  m.vertices.assign(d.vertices.begin(), d.vertices.end());
  if (d.facet_begin.empty()) {  // flat hull: one polygon through its vertices
    m.polygon_begin = {0};
    for (std::uint32_t k = 0; k < d.vertices.size(); ++k) m.indices.push_back(k);
    m.polygon_begin.push_back(static_cast<std::uint32_t>(m.indices.size()));
    return;
  }
  m.polygon_begin.assign(d.facet_begin.begin(), d.facet_begin.end());
  m.indices.assign(d.facet_vertices.begin(), d.facet_vertices.end());
}

}  // namespace

std::optional<std::string> read_file(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return std::nullopt;
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return std::move(bytes).str();
}

void write_file_atomically(const std::filesystem::path& file, const std::string& text) {
  const std::filesystem::path tmp = file.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  std::filesystem::rename(tmp, file);
}

namespace {

// A surface's or a shell's own triangles (not its hull).
DisplayMesh triangles_mesh(std::span<const Vec3> vertices, std::span<const TriangleIndices> triangles) {
  DisplayMesh m;
  m.vertices.assign(vertices.begin(), vertices.end());
  m.polygon_begin.push_back(0);
  for (const TriangleIndices& tri : triangles) {
    m.indices.insert(m.indices.end(), tri.begin(), tri.end());
    m.polygon_begin.push_back(static_cast<std::uint32_t>(m.indices.size()));
  }
  return m;
}

}  // namespace

DisplayMesh display_mesh(const dem::ShapeTemplate& t) {
  if (t.surface_grain) return triangles_mesh(t.surface->vertices, t.surface->triangles);
  if (t.shell) return triangles_mesh(t.shell->vertices, t.shell->triangles);
  if (t.parts.empty()) return display_mesh(t.shape);
  DisplayMesh m;
  for (const dem::TemplatePart& p : t.parts) {
    const DisplayMesh part = p.surface_grain ? triangles_mesh(p.surface->vertices, p.surface->triangles) : display_mesh(p.shape);
    const std::uint32_t first = static_cast<std::uint32_t>(m.vertices.size()), at = static_cast<std::uint32_t>(m.indices.size());
    for (const Vec3& v : part.vertices) m.vertices.push_back(apply(p.pose, v));
    for (const std::uint32_t i : part.indices) m.indices.push_back(first + i);
    if (m.polygon_begin.empty()) m.polygon_begin.push_back(0);
    for (std::size_t k = 1; k < part.polygon_begin.size(); ++k) m.polygon_begin.push_back(at + part.polygon_begin[k]);
  }
  return m;
}

DisplayMesh display_mesh(const Shape& shape) {
  DisplayMesh m;
  if (shape.margin == 0) {
    if (const auto* p = std::get_if<Polytope>(&shape.core)) {
      polytope_mesh(*p->data, m);
      return m;
    }
  }
  if (const auto* t = std::get_if<Triangle>(&shape.core); t && shape.margin >= 0) {
    m.vertices = {t->v[0], t->v[1], t->v[2]};
    m.polygon_begin = {0, 3};
    m.indices = {0, 1, 2};
    return m;
  }
  polytope_mesh(*tessellate(shape, kDisplayDirections).polytope.data, m);
  return m;
}

void write_vtk_frame(const std::filesystem::path& file, const dem::World& w, std::span<const DisplayMesh> meshes) {
  std::size_t points = 0, polygons = 0, indices = 0;
  for (const dem::Body& b : w.bodies) {
    const DisplayMesh& m = meshes[b.shape];
    points += m.vertices.size();
    polygons += m.polygon_begin.empty() ? 0 : m.polygon_begin.size() - 1;
    indices += m.indices.size();
  }
  std::string out = "# vtk DataFile Version 3.0\ngjkdem frame t=";
  append_number(out, w.time);
  out += "\nBINARY\nDATASET POLYDATA\nPOINTS " + std::to_string(points) + " double\n";
  for (const dem::Body& b : w.bodies) {
    const Transform pose = dem::shape_pose(w, b);
    for (const Vec3& v : meshes[b.shape].vertices) {
      const Vec3 p = apply(pose, v);
      put_big_endian(out, p.x), put_big_endian(out, p.y), put_big_endian(out, p.z);
    }
  }
  out += "\nPOLYGONS " + std::to_string(polygons) + " " + std::to_string(polygons + indices) + "\n";
  std::int32_t base = 0;
  for (const dem::Body& b : w.bodies) {
    const DisplayMesh& m = meshes[b.shape];
    for (std::size_t k = 0; k + 1 < m.polygon_begin.size(); ++k) {
      put_big_endian(out, static_cast<std::int32_t>(m.polygon_begin[k + 1] - m.polygon_begin[k]));
      for (std::uint32_t i = m.polygon_begin[k]; i < m.polygon_begin[k + 1]; ++i)
        put_big_endian(out, static_cast<std::int32_t>(base + m.indices[i]));
    }
    base += static_cast<std::int32_t>(m.vertices.size());
  }
  out += "\nCELL_DATA " + std::to_string(polygons) + "\nSCALARS body_id int 1\nLOOKUP_TABLE default\n";
  auto per_cell = [&](auto&& write) {
    for (const dem::Body& b : w.bodies) {
      const DisplayMesh& m = meshes[b.shape];
      for (std::size_t k = 0; k + 1 < m.polygon_begin.size(); ++k) write(b);
    }
  };
  per_cell([&](const dem::Body& b) { put_big_endian(out, static_cast<std::int32_t>(b.id)); });
  out += "\nSCALARS fixed int 1\nLOOKUP_TABLE default\n";
  per_cell([&](const dem::Body& b) { put_big_endian(out, static_cast<std::int32_t>(b.fixed)); });
  Real values[dem::kMaxChannelComponents];
  for (const dem::BodyChannel& ch : dem::kBodyChannels) {
    if (!(ch.use & dem::kChannelVtk) || !ch.in_outputs_of(w)) continue;
    out += "\n";
    if (ch.components == 3) out += "VECTORS " + std::string(ch.name) + " float\n";
    else out += "SCALARS " + std::string(ch.name) + " float " + std::to_string(ch.components) + "\nLOOKUP_TABLE default\n";
    per_cell([&](const dem::Body& b) {
      ch.read(w, b, values);
      for (std::uint32_t k = 0; k < ch.components; ++k) put_big_endian(out, static_cast<float>(values[k]));
    });
  }
  out += "\n";
  std::ofstream f(file, std::ios::binary);
  f.write(out.data(), static_cast<std::streamsize>(out.size()));
  if (!f) throw std::runtime_error("cannot write frame " + file.string());
}

void write_frame_series(const std::filesystem::path& file, std::span<const std::pair<std::string, Real>> frames) {
  std::string out = "{\n  \"file-series-version\": \"1.0\",\n  \"files\": [\n";
  for (std::size_t k = 0; k < frames.size(); ++k) {
    out += "    {\"name\": \"" + frames[k].first + "\", \"time\": ";
    append_number(out, frames[k].second);
    out += k + 1 < frames.size() ? "},\n" : "}\n";
  }
  out += "  ]\n}\n";
  std::ofstream f(file, std::ios::binary);
  f << out;
  if (!f) throw std::runtime_error("cannot write " + file.string());
}

std::vector<TracedBody> traced_bodies(const dem::World& w) {
  std::vector<TracedBody> out;
  for (const dem::BodyName& n : w.names) {
    if (const std::size_t i = dem::index_of_body(w.bodies, n.id); i < w.bodies.size())
      out.push_back({n.name, static_cast<std::uint32_t>(i)});
  }
  return out;
}

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  const long s = std::lround(seconds);
  char buf[32];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, s / 60 % 60);
  else std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  return buf;
}

std::string progress_line(Real time, Real duration, std::uint64_t step, std::uint64_t steps_total,
                          double steps_per_second) {
  const double eta = steps_per_second > 0 ? static_cast<double>(steps_total - std::min(step, steps_total)) /
                                                steps_per_second
                                          : -1;
  const double fraction = steps_total ? static_cast<double>(step) / static_cast<double>(steps_total) : 1;
  char line[200];
  std::snprintf(line, sizeof line, "t = %.4f / %.4g s  %5.1f%%  %.0f steps/s  ETA %s", time, duration, 100 * fraction,
                steps_per_second, duration_text(eta).c_str());
  return line;
}

ProgressClock::ProgressClock(bool terminal, std::uint64_t first_step)
    : terminal_(terminal), first_(first_step), start_(std::chrono::steady_clock::now()), last_(start_) {}

std::string ProgressClock::due(Real time, Real duration, std::uint64_t step, std::uint64_t steps_total, bool final) {
  const auto now = std::chrono::steady_clock::now();
  if (!final && std::chrono::duration<double>(now - last_).count() < (terminal_ ? 0.25 : 10.0)) return "";
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(step - std::min(step, first_)) / elapsed : 0;
  return progress_line(time, duration, step, steps_total, rate);
}

std::string trace_header() {
  std::string s = "time,name";
  for (const dem::BodyChannel& ch : dem::kBodyChannels)
    if (ch.use & dem::kChannelTraced) s.append(",").append(ch.columns);
  return s + "\n";
}

std::string trace_row(const dem::World& w, const std::string& name, const dem::Body& b) {
  std::string s;
  append_number(s, w.time);
  s += "," + name;
  Real values[dem::kMaxChannelComponents];
  for (const dem::BodyChannel& ch : dem::kBodyChannels) {
    if (!(ch.use & dem::kChannelTraced)) continue;
    ch.read(w, b, values);
    for (std::uint32_t k = 0; k < ch.components; ++k) {
      s += ',';
      append_number(s, values[k]);
    }
  }
  s += '\n';
  return s;
}

std::string energy_header(EnergyColumns columns) {
  return std::string("time,kinetic,potential,elastic,dissipated,contacts,wall_work,inflow_energy") +
         (columns.split ? ",split_energy" : "") + (columns.applied ? ",applied_work\n" : "\n");
}

std::string cell_header() {
  return "time,lx,ly,lz,tilt_xy,tilt_xz,tilt_yz,volume,rate_xx,rate_yy,rate_zz,rate_xy,rate_xz,rate_yz,stress_xx,"
         "stress_yy,stress_zz,stress_xy,stress_xz,stress_yz\n";
}

std::string cell_row(const dem::World& w) {
  const dem::PeriodicCell& c = w.cell.now;
  const Vec3 size = c.hi - c.lo;
  std::string s;
  append_number(s, w.time);
  for (const Real v : {size.x, size.y, size.z, c.tilt.x, c.tilt.y, c.tilt.z, dem::cell_volume(c)}) {
    s += ',';
    append_number(s, v);
  }
  for (const dem::CellTensor* t : {&w.cell.rate, &w.cell.stress})
    for (const Real v : *t) {
      s += ',';
      append_number(s, v);
    }
  s += "\n";
  return s;
}

std::string energy_row(Real time, const dem::EnergyBalance& e, int contacts, EnergyColumns columns) {
  std::string s;
  for (Real v : {time, e.kinetic, e.potential, e.elastic, e.dissipated}) {
    append_number(s, v);
    s += ',';
  }
  s += std::to_string(contacts) + ",";
  append_number(s, e.wall_work);
  s += ',';
  append_number(s, e.inflow);
  if (columns.split) {
    s += ',';
    append_number(s, e.split);
  }
  if (columns.applied) {
    s += ',';
    append_number(s, e.applied_work);
  }
  s += "\n";
  return s;
}

}  // namespace gjkdem::io
