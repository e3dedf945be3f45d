// The view format (docs/view-format.md): a settled bed of polyhedra, balls
// and L-shaped compounds on a floor, in a box, written and read back. The
// frame holds what the world holds (to single precision); the templates'
// surfaces placed by a frame's poses are where the world's shapes are; the
// triangles face outwards; the contacts of a frame, with gravity, give back
// every body's force (none missing, signs right); the size is the documented
// one; readers refuse damaged files; a resumed writer cuts its index back.
#include "gjkdem/io/view_format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <fstream>
#include <random>

#include <unistd.h>

#include "dem/beds.hpp"
#include "gjkdem/dem/run.hpp"
#include "gjkdem/io/run_observers.hpp"
#include "gjkdem/io/run_output.hpp"

namespace gjkdem::io {
namespace {

namespace fs = std::filesystem;

dem::World settled_bed() {
  dem::WorldSettings settings;
  settings.model = dem::ContactModel::Hertz;
  dem::WorldBuilder b(settings);
  const std::uint32_t m = b.add_material({"rock", 2500, 1e7, 0.25, 0.3, 0.5});
  b.add_plane({0, 0, 0}, {0, 0, 1}, m, "floor");
  b.add_box_walls({-0.05, -0.05, 0}, {0.05, 0.05, 0.2}, true, 0.01, m, "box");
  std::mt19937_64 rng(5);
  dem::test::fill_polyhedra(b, {.count = 30, .variants = 3, .vertices = 12, .size = 0.015, .lo = {-0.04, -0.04, 0.01},
                                .hi = {0.04, 0.04, 0.06}, .material = m},
                            rng);
  b.add_body({.shape = {Shape{Point{}, 0.006}, {}}, .material = m, .position = {0.01, 0.0, 0.08}});
  b.add_body({.shape = {.parts = {{Shape{Box{{0.01, 0.0025, 0.0025}}}, Transform::from({0.01, 0, 0.0025}, Quat{})},
                                  {Shape{Box{{0.0025, 0.0025, 0.0075}}}, Transform::from({0.0025, 0, 0.0125}, Quat{})}}},
              .material = m,
              .position = {-0.02, 0.01, 0.1},
              .rotation = quat_from_axis_angle(normalized(Vec3{1, 2, 3}), 0.7)});
  dem::World w = b.build();
  dem::RunState run = dem::plan_run(0.15, dem::critical_time_step(w), 0.15);
  const dem::RunOutcome outcome = dem::run(w, run, {});
  EXPECT_EQ(outcome.status, dem::RunStatus::Completed) << outcome.error;
  return w;
}

const dem::World& bed() {
  static const dem::World w = settled_bed();
  return w;
}

Vec3 at(const std::vector<float>& a, std::size_t k) { return {a[3 * k], a[3 * k + 1], a[3 * k + 2]}; }

TEST(ViewFormat, AFrameHoldsTheWorldAndReadsBackTheSame) {
  const dem::World& w = bed();
  const ViewFrame f = view_frame(w, 77);
  ASSERT_EQ(f.body_count(), w.bodies.size());
  EXPECT_GT(f.contact_count(), 30u) << "a settled bed touches";
  EXPECT_EQ(f.time, w.time);
  EXPECT_EQ(f.step, 77u);
  for (std::size_t k = 0; k < w.bodies.size(); ++k) {
    const dem::Body& b = w.bodies[k];
    EXPECT_LT(length(at(f.positions, k) - b.position), 1e-7);
    EXPECT_EQ(f.ids[k], b.id);
    EXPECT_EQ(f.templates[k], b.shape);
    EXPECT_EQ(f.flags[k] & kViewFixed, b.fixed ? kViewFixed : 0);
  }
  const std::string bytes = encode(f);
  const std::size_t planes = w.planes.size();
  EXPECT_EQ(bytes.size(), 40 + 61 * f.body_count() + (4 - f.body_count() % 4) % 4 + 44 * f.contact_count() + 24 * planes +
                              40 + 4 + 21 * f.bond_count() + (4 - 21 * f.bond_count() % 4) % 4 + 4)
      << "the size docs/view-format.md gives (no channels: the bed has no applied loads)";
  const ViewFrame back = decode_view_frame(bytes);
  EXPECT_EQ(back.time, f.time);
  EXPECT_EQ(back.positions, f.positions);
  EXPECT_EQ(back.orientations, f.orientations);
  EXPECT_EQ(back.angular_velocities, f.angular_velocities);
  EXPECT_EQ(back.flags, f.flags);
  EXPECT_EQ(back.contact_a, f.contact_a);
  EXPECT_EQ(back.contact_forces, f.contact_forces);
  EXPECT_EQ(back.plane_normals, f.plane_normals);
  EXPECT_EQ(encode(back), bytes);
}

// Issue 54, point 11: positions beyond float's range (3.4e38 m) became inf
// in the frames, and analyze then refused the folder. Every position the
// builder takes (up to 1e100 m; beyond, refused) gives finite frames, at
// float's largest with its sign where it is beyond float's range.
TEST(ViewFormat, FramesStayFiniteForEveryPositionTheBuilderTakes) {
  for (const Real x : {1e30, 1e39, 1e100, -1e100}) {
    dem::WorldBuilder b;
    const std::uint32_t m = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
    b.add_body({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .material = m, .position = {x, 0, 0},
                .velocity = {1e45, 0, 0}});
    const dem::World w = b.build();
    const ViewFrame f = view_frame(w, 0);
    for (const std::vector<float>* v : {&f.positions, &f.velocities})
      for (const float c : *v) EXPECT_TRUE(std::isfinite(c)) << x;
    EXPECT_EQ(f.positions[0], x > std::numeric_limits<float>::max() ? std::numeric_limits<float>::max()
                              : x < -std::numeric_limits<float>::max() ? -std::numeric_limits<float>::max()
                                                                       : static_cast<float>(x));
    EXPECT_EQ(decode_view_frame(encode(f)).positions, f.positions);
  }
  dem::WorldBuilder b;
  const std::uint32_t m = b.add_material({"rock", 2500, 1e7, 0.25, 0.5, 0.5});
  try {
    b.add_body({.shape = {Shape{Box{{0.01, 0.01, 0.01}}}, {}}, .material = m, .position = {0, 1.1e100, 0}, .label = "far"});
    b.build();
    ADD_FAILURE() << "a position beyond 1e100 m was taken";
  } catch (const dem::BuildError& e) {
    EXPECT_NE(std::string(e.what()).find("far: position is outside the supported range [-1e100, 1e100] m"),
              std::string::npos) << e.what();
  }
}

// Each body's force is gravity plus what its contacts in the frame give:
// a contact missing, counted twice or with the wrong sign would show.
TEST(ViewFormat, TheContactsGiveBackEveryBodysForce) {
  const dem::World& w = bed();
  const ViewFrame f = view_frame(w, 0);
  std::vector<Vec3> force(f.body_count());
  for (std::size_t c = 0; c < f.contact_count(); ++c) {
    const Vec3 on_b = at(f.contact_forces, c);
    force[f.contact_b[c]] += on_b;
    if (!(f.contact_a[c] & kViewPlaneSide)) force[f.contact_a[c]] -= on_b;
  }
  Real largest = 0;
  for (const dem::Body& b : w.bodies) largest = std::fmax(largest, length(b.force));
  int checked = 0;
  for (std::size_t k = 0; k < w.bodies.size(); ++k) {
    const dem::Body& b = w.bodies[k];
    if (b.fixed) continue;
    const Vec3 expected = b.force - w.settings.gravity * dem::mass_of(w, b);
    EXPECT_LT(length(force[k] - expected), 1e-5 * largest) << "body " << b.id;
    ++checked;
  }
  EXPECT_EQ(checked, 32);
}

// A template's vertices placed by a frame's pose land where the world's
// shape puts them; its triangles face away from the body's centre of mass.
TEST(ViewFormat, SurfacesPlacedByFramePosesAreTheWorldsShapes) {
  const dem::World& w = bed();
  const ViewShapes shapes = decode_view_shapes(encode(view_shapes(w)));
  ASSERT_EQ(shapes.templates.size(), w.templates.size());
  EXPECT_EQ(shapes.plane_ids.size(), 1u);
  const ViewFrame f = view_frame(w, 0);
  for (std::size_t k = 0; k < w.bodies.size(); ++k) {
    const dem::Body& b = w.bodies[k];
    const ViewMesh& mesh = shapes.templates[b.shape];
    const DisplayMesh display = display_mesh(w.templates[b.shape]);
    ASSERT_EQ(mesh.vertices.size(), 3 * display.vertices.size());
    const Quat q{f.orientations[4 * k], f.orientations[4 * k + 1], f.orientations[4 * k + 2], f.orientations[4 * k + 3]};
    const Transform frame_pose = Transform::from(at(f.positions, k), q);
    const Transform world_pose = dem::shape_pose(w, b);
    for (std::size_t v = 0; v < display.vertices.size(); ++v)
      ASSERT_LT(length(apply(frame_pose, at(mesh.vertices, v)) - apply(world_pose, display.vertices[v])), 1e-6)
          << "body " << b.id << " vertex " << v;
    if (b.fixed || !w.templates[b.shape].parts.empty()) continue;  // a compound's centre may lie outside a part
    for (std::size_t t = 0; 3 * t < mesh.triangles.size(); ++t) {
      const Vec3 p0 = at(mesh.vertices, mesh.triangles[3 * t]), p1 = at(mesh.vertices, mesh.triangles[3 * t + 1]),
                 p2 = at(mesh.vertices, mesh.triangles[3 * t + 2]);
      EXPECT_GT(dot(cross(p1 - p0, p2 - p0), (p0 + p1 + p2) / 3), 0) << "template " << b.shape << " triangle " << t;
    }
  }
}

TEST(ViewFormat, DamagedFilesAreRefused) {
  const dem::World& w = bed();
  const std::string frame = encode(view_frame(w, 0)), shapes = encode(view_shapes(w));
  auto refused = [](auto decode, const std::string& bytes, const std::string& why) {
    try {
      decode(bytes);
      ADD_FAILURE() << "accepted: " << why;
    } catch (const ViewFormatError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  refused(decode_view_frame, frame.substr(0, frame.size() - 5), "cut short");
  refused(decode_view_frame, frame.substr(0, 30), "cut short");
  refused(decode_view_frame, frame + "x", "past its end");
  // Cut inside the padding after the flags (the bed's body count is not a
  // multiple of 4): refused, not read past the end.
  const std::size_t flags_end = 40 + 61 * bed().bodies.size();
  ASSERT_NE(flags_end % 4, 0u);
  refused(decode_view_frame, frame.substr(0, flags_end + 1), "cut short");
  std::string padded = frame;
  padded[flags_end] = 7;
  refused(decode_view_frame, padded, "padding");
  refused(decode_view_frame, shapes, "wrong magic");
  refused(decode_view_shapes, frame, "wrong magic");
  refused(decode_view_shapes, shapes.substr(0, shapes.size() / 2), "");
  std::string newer = frame;
  newer[8] = 5;
  refused(decode_view_frame, newer, "version 5");
  // A version 3 frame (no channel block: it ends with the bonds) and a
  // version 2 one (no bonds: it ends with the cell) are still read.
  for (const auto& [version, cut] : {std::pair{3, 4}, std::pair{2, 8}}) {
    std::string older = frame.substr(0, frame.size() - cut);
    older[8] = static_cast<char>(version);
    EXPECT_EQ(decode_view_frame(older).body_count(), bed().bodies.size()) << "version " << version;
  }
  std::string cell = frame;
  cell[cell.size() - 48] = 8;  // the periodic axes' bits (then the cell, no bonds, no channels)
  refused(decode_view_frame, cell, "periodic axes");
  // A contact naming a body the frame does not have.
  const ViewFrame f = decode_view_frame(frame);
  ViewFrame bad = f;
  bad.contact_b[0] = static_cast<std::uint32_t>(f.body_count());
  refused(decode_view_frame, encode(bad), "naming a body");
  // A bond naming a body the frame does not have, or a state it cannot have.
  ViewFrame bonded = f;
  bonded.bond_first = {0}, bonded.bond_second = {static_cast<std::uint32_t>(f.body_count())};
  bonded.bond_points = {0, 0, 0}, bonded.bond_intact = {1};
  refused(decode_view_frame, encode(bonded), "bond 0");
  bonded.bond_second = {1}, bonded.bond_intact = {2};
  refused(decode_view_frame, encode(bonded), "bond 0");
  bonded.bond_intact = {0};
  EXPECT_EQ(decode_view_frame(encode(bonded)).bond_count(), 1u);
  bad = f;
  bad.contact_a[0] = kViewPlaneSide + 1;
  refused(decode_view_frame, encode(bad), "naming a body or plane");
}

// The channel block holds the table's framed channels whose feature is on,
// by name: applied loads while the world has them, none otherwise.
TEST(ViewFormat, AppliedLoadsTravelAsNamedChannels) {
  dem::World w = bed();
  EXPECT_TRUE(view_frame(w, 0).channels.empty());
  w.applied_loads = true;
  for (std::size_t k = 0; k < w.bodies.size(); ++k) {
    const Real s = static_cast<Real>(k);
    w.bodies[k].applied_force = {s, 2 * s, -0.5 * s}, w.bodies[k].applied_torque = {0, -s, 0.25};
  }
  const ViewFrame f = decode_view_frame(encode(view_frame(w, 3)));
  ASSERT_EQ(f.channels.size(), 2u);
  EXPECT_EQ(f.channels[0].name, "applied_force");
  EXPECT_EQ(f.channels[0].unit, "N");
  EXPECT_EQ(f.channels[1].name, "applied_torque");
  EXPECT_EQ(f.channels[1].unit, "N m");
  for (const ViewChannel& c : f.channels) {
    ASSERT_EQ(c.components, 3u);
    ASSERT_EQ(c.values.size(), 3 * w.bodies.size());
  }
  for (std::size_t k = 0; k < w.bodies.size(); ++k) {
    const Vec3 force = at(f.channels[0].values, k), torque = at(f.channels[1].values, k);
    for (int a = 0; a < 3; ++a) {
      EXPECT_FLOAT_EQ(force[a], static_cast<float>(w.bodies[k].applied_force[a]));
      EXPECT_FLOAT_EQ(torque[a], static_cast<float>(w.bodies[k].applied_torque[a]));
    }
  }
  // Damaged blocks are refused, naming the channel.
  auto refused = [](ViewFrame bad, const std::string& why) {
    try {
      decode_view_frame(encode(bad));
      ADD_FAILURE() << "accepted: " << why;
    } catch (const ViewFormatError& e) {
      EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
  };
  ViewFrame bad = f;
  bad.channels[1].name = "applied_force";
  refused(bad, "twice");
  bad = f, bad.channels[0].name = "Applied force";
  refused(bad, "lower case");
  bad = f, bad.channels[0].name = "";
  refused(bad, "name");
  bad = f, bad.channels[0].components = 5, bad.channels[0].values.resize(5 * w.bodies.size());
  refused(bad, "size");
  bad = f, bad.channels[0].unit = "N\n";
  refused(bad, "printable");
  bad = f, bad.channels[1].values.pop_back();
  refused(bad, "cut short");
}

TEST(ViewFormat, AResumedWriterCutsItsIndexBackToTheCheckpoint) {
  const fs::path dir = fs::temp_directory_path() / ("gjkdem_view_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const dem::World& w = bed();
  {
    ViewWriter writer(dir, w, true, 0);
    dem::RunState state;
    for (state.outputs = 1; state.outputs <= 5; ++state.outputs) writer.on_output(w, state);
  }
  EXPECT_EQ(read_view_index(view_index_file(dir)).size(), 5u);
  {
    ViewWriter resumed(dir, w, true, 3);
    const std::vector<ViewIndexRow> rows = read_view_index(view_index_file(dir));
    ASSERT_EQ(rows.size(), 3u);
    EXPECT_EQ(rows.back().frame, 2u);
    dem::RunState state;
    state.outputs = 4;
    resumed.on_output(w, state);
  }
  const std::vector<ViewIndexRow> rows = read_view_index(view_index_file(dir));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows.back().frame, 3u);
  EXPECT_EQ(rows.back().bodies, w.bodies.size());
  EXPECT_EQ(read_view_frame(view_frame_file(dir, 3)).body_count(), w.bodies.size());
  // An index that is not one is refused, not half read.
  std::ofstream(view_index_file(dir), std::ios::app) << "4,0.1,x\n";
  EXPECT_THROW(read_view_index(view_index_file(dir)), ViewFormatError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gjkdem::io
