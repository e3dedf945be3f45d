// Checkpoints (docs/checkpoints.md): a world saved and restored continues
// with the same bits as one that never stopped; every damaged, foreign or
// edited checkpoint is refused with a message saying why, and nothing in
// the world changes then.
#include "gjkdem/io/checkpoint.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "gjkdem/dem/world_builder.hpp"
#include "dem/beds.hpp"
#include "gjkdem/shape/shape_factories.hpp"

namespace gjkdem::io {
namespace {

// 40 random polyhedra poured into a box of plane walls, run for a while so
// that contacts, springs and warm starts exist. `driven`: the floor vibrates,
// a paddle (a box) turns through the bed, an inflow adds grains from above
// and an L-shaped compound stands on the floor.
dem::World pour(std::uint64_t seed, int grains = 40, bool driven = false, Real friction = 0.5) {
  dem::WorldBuilder b;
  const std::uint32_t rock = b.add_material({"rock", 2500, 1e6, 0.25, 0.4, friction});
  std::uint32_t shake = 0, turn = 0;
  if (driven) {
    shake = b.add_motion({.amplitude = {0, 0, 0.002}, .frequency = 30}, "shake");
    turn = b.add_motion({.center = {0, 0, 0.02}, .angular_velocity = {0, 3, 0}}, "turn");
    b.add_body({.shape = {Shape{Box{{0.02, 0.03, 0.002}}}, {}}, .material = rock, .position = {0, 0, 0.02},
                .fixed = true, .motion = turn, .label = "paddle"});
    dem::InflowDef inflow;
    inflow.variants = {{Shape{Box{{0.004, 0.004, 0.004}}}, {}}, {make_sphere(0.004), {}}};
    inflow.lo = {-0.03, -0.03, 0.15};
    inflow.hi = {0.03, 0.03, 0.16};
    inflow.material = rock;
    inflow.rate = 400;
    inflow.stop = 1;
    b.add_inflow(inflow);
    const std::vector<PlacedShape> ell = {
        {Shape{Box{{0.01, 0.003, 0.003}}}, Transform::from({0.01, 0, 0.003}, Quat{})},
        {Shape{Box{{0.003, 0.003, 0.007}}}, Transform::from({0.003, 0, 0.013}, Quat{})}};
    b.add_body({.shape = {.parts = ell}, .material = rock, .position = {-0.025, 0, 0.01845},
                .rotation = quat_from_axis_angle({0, 1, 0}, 0.75 * kPi), .label = "ell"});  // on both tips
  }
  b.add_plane({0, 0, 0}, {0, 0, 1}, rock, "floor", shake);
  b.add_plane({-0.04, 0, 0}, {1, 0, 0}, rock, "-x");
  b.add_plane({0.04, 0, 0}, {-1, 0, 0}, rock, "+x");
  std::mt19937_64 rng(seed);
  dem::test::fill_polyhedra(b,
                            {.count = static_cast<std::size_t>(grains), .size = 0.015, .lo = {-0.04, -0.04, 0},
                             .hi = {0.04, 0.04, 0.12}, .material = rock},
                            rng);
  return b.build();
}

bool same_state(const dem::World& a, const dem::World& b) {
  if (a.bodies.size() != b.bodies.size() || a.time != b.time) return false;
  for (std::size_t i = 0; i < a.bodies.size(); ++i)
    if (std::memcmp(&a.bodies[i], &b.bodies[i], sizeof(dem::Body)) != 0) return false;
  return true;
}

TEST(Checkpoint, RestoredWorldContinuesWithTheSameBits) {
  for (const bool driven : {false, true}) {
    SCOPED_TRACE(driven ? "driven walls" : "fixed walls");
    dem::World straight = pour(1, 40, driven);
    const dem::RunState plan = dem::plan_run(0.08, 1e-4, 0.01);
    dem::RunState run = plan;
    ASSERT_EQ(dem::run(straight, run, {}).status, dem::RunStatus::Completed);

    dem::World first = pour(1, 40, driven);
    dem::RunState part = plan;
    struct PartWatch : dem::RunObserver {  // contacts of a compound's second part: keys with parts
      int seen = 0;
      void on_output(const dem::World&, const dem::RunState&) override {}
      void on_step(const dem::World& w, const dem::RunState&) override {
        for (const dem::StepContact& c : w.results.contacts) seen += c.active && (c.part_a > 0 || c.part_b > 0);
      }
    } parts;
    dem::RunObserver* watch[] = {&parts};
    dem::run(first, part, watch, [&] { return part.step == 500; });
    ASSERT_EQ(part.step, 500u);
    ASSERT_GT(first.stats.contacts, 5);  // springs and warm starts to carry
    if (driven) {
      ASSERT_NE(first.wall_work, 0);
      ASSERT_GT(first.inflow_states[0].inserted, 10u);  // bodies beyond the scene's to restore
      ASSERT_GT(parts.seen, 0);
    }
    const std::string bytes = encode_checkpoint(first, {part, {}}, 42);
    dem::World resumed = pour(1, 40, driven);  // a world rebuilt from the same "scene"
    const Checkpoint c = decode_checkpoint(bytes, resumed, 42, "memory");
    dem::RunState rest = c.run;
    ASSERT_EQ(dem::run(resumed, rest, {}).status, dem::RunStatus::Completed);
    EXPECT_TRUE(same_state(straight, resumed));
    EXPECT_EQ(straight.wall_work, resumed.wall_work);
    for (std::size_t k = 0; k < straight.planes.size(); ++k)
      EXPECT_TRUE(straight.planes[k].point == resumed.planes[k].point) << "plane " << k;
  }
}

std::string refusal(const std::string& bytes, dem::World& w, std::uint64_t fingerprint = 42) {
  const dem::World before = w;
  try {
    decode_checkpoint(bytes, w, fingerprint, "ck");
  } catch (const CheckpointError& e) {
    EXPECT_TRUE(same_state(before, w)) << "the world changed on a refused checkpoint";
    return e.what();
  }
  return "(accepted)";
}

// A checkpoint saved before any box was made (no anchors) restores into a
// world that has run since as into a fresh one: nothing of the stepped
// world's broad-phase cache (box anchors, search cell) survives the load.
TEST(Checkpoint, ACheckpointWithoutAnchorsLeavesNoneOfTheWorldsOwn) {
  const dem::World start = pour(2, 30);
  const std::string bytes = io::encode_checkpoint(start, {dem::plan_run(0.02, 1e-4, 0.01), {}}, 5);
  dem::World fresh = pour(2, 30), stepped = pour(2, 30);
  for (int i = 0; i < 50; ++i) ASSERT_EQ(dem::step(stepped, 1e-4).status, dem::StepStatus::Ok);
  ASSERT_FALSE(stepped.search.boxes.anchor_position.empty());
  dem::RunState a = io::decode_checkpoint(bytes, fresh, 5, "memory").run;
  dem::RunState b = io::decode_checkpoint(bytes, stepped, 5, "memory").run;
  EXPECT_TRUE(stepped.search.boxes.anchor_position.empty());
  ASSERT_EQ(dem::run(fresh, a, {}).status, dem::RunStatus::Completed);
  ASSERT_EQ(dem::run(stepped, b, {}).status, dem::RunStatus::Completed);
  EXPECT_TRUE(same_state(fresh, stepped));
}

TEST(Checkpoint, DamagedForeignAndEditedCheckpointsAreRefused) {
  dem::World w = pour(2);
  dem::RunState run = dem::plan_run(0.02, 1e-4, 0.01);
  dem::run(w, run, {});
  const std::string good = encode_checkpoint(w, {run, {}}, 42);
  dem::World target = pour(2);
  EXPECT_EQ(refusal(good, target), "(accepted)");

  dem::World fresh = pour(2);
  EXPECT_NE(refusal(good, fresh, 43).find("another scene"), std::string::npos);
  dem::World other = pour(3);  // same body count, other shapes and places
  EXPECT_NE(refusal(encode_checkpoint(w, {run, {}}, 7), other, 42).find("another scene"), std::string::npos);
  dem::World fewer = pour(2, 30);
  EXPECT_NE(refusal(good, fewer).find("the scene has 30 bodies, the checkpoint 40"), std::string::npos);

  // Every single-bit flip is caught: by the checksum, or the header's checks.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    std::string bad = good;
    const std::size_t at = rng() % bad.size();
    bad[at] = static_cast<char>(bad[at] ^ (1 << (rng() % 8)));
    dem::World t = pour(2);
    const std::string why = refusal(bad, t);
    EXPECT_NE(why, "(accepted)") << "flip at byte " << at;
  }
  // Truncated anywhere, extended, another version, another program's file.
  for (std::size_t keep : {std::size_t{0}, std::size_t{7}, std::size_t{20}, std::size_t{40}, good.size() / 2,
                           good.size() - 1}) {
    dem::World t = pour(2);
    EXPECT_NE(refusal(good.substr(0, keep), t), "(accepted)") << keep;
  }
  dem::World t = pour(2);
  EXPECT_NE(refusal(good + "x", t).find("length"), std::string::npos);
  std::string v2 = good;
  v2[8] = 2;
  EXPECT_NE(refusal(v2, t).find("format 2"), std::string::npos);
  EXPECT_NE(refusal("gjkdckp2 old bytes", t).find("older gjkdem format"), std::string::npos);
  EXPECT_NE(refusal("hello", t).find("not a gjkdem checkpoint"), std::string::npos);
}

// A new run from a saved state (Restore::NewRun): the bodies, springs and
// warm starts carry over, the clock starts at 0 and the forces are worked out
// anew under the world's own materials and gravity; what the world is made of
// (bodies, shapes, fixed bodies' places, plane walls) must be as it was, and
// each difference is refused by name, the world left as it was.
TEST(Checkpoint, ANewRunStartsFromAStateWithOtherMaterialsButNotOtherBodies) {
  dem::World w = pour(2, 40, true);
  dem::RunState run = dem::plan_run(0.03, 1e-4, 0.01);
  ASSERT_EQ(dem::run(w, run, {}).status, dem::RunStatus::Completed);
  ASSERT_GT(w.stats.contacts, 5);
  ASSERT_NE(w.wall_work, 0);
  const std::string bytes = encode_checkpoint(w, {run, {}}, 42);

  dem::World slick = pour(2, 40, true, 0.1);  // other friction, other gravity, another scene's fingerprint
  slick.settings.gravity = {0, 0, -3};
  decode_checkpoint(bytes, slick, 7, "ck", Restore::NewRun);
  EXPECT_EQ(slick.time, 0);
  EXPECT_EQ(slick.wall_work, 0);
  EXPECT_FALSE(slick.forces_current);
  ASSERT_EQ(slick.bodies.size(), w.bodies.size());
  for (std::size_t i = 0; i < w.bodies.size(); ++i)
    if (!w.bodies[i].motion) {
      EXPECT_TRUE(slick.bodies[i].position == w.bodies[i].position) << i;
    }
  EXPECT_EQ(slick.pairs.size(), w.pairs.size());
  EXPECT_EQ(slick.materials[0].friction, 0.1);
  dem::RunState next = dem::plan_run(0.01, 1e-4, 0.01);
  EXPECT_EQ(dem::run(slick, next, {}).status, dem::RunStatus::Completed);
  dem::World same_run = pour(2, 40, true, 0.1);
  EXPECT_NE(refusal(bytes, same_run, 7).find("--from"), std::string::npos)
      << "the same run with another fingerprint points to a new run";

  const auto refused = [&](dem::World other) {
    const dem::World before = other;
    try {
      decode_checkpoint(bytes, other, 42, "ck", Restore::NewRun);
    } catch (const CheckpointError& e) {
      EXPECT_TRUE(same_state(before, other)) << "the world changed on a refused checkpoint";
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string fewer = refused(pour(2, 39, true));  // one grain fewer, with an inflow
  EXPECT_NE(fewer.find("the scene has 41 bodies, the checkpoint"), std::string::npos) << fewer;
  dem::World reshaped = pour(2, 40, true);
  const std::uint32_t shape = reshaped.bodies.back().shape;
  reshaped.templates[shape].reach *= 1.5;
  std::size_t first = 0;  // the first body of that shape is named
  while (reshaped.bodies[first].shape != shape) ++first;
  const std::string why = refused(reshaped);
  EXPECT_NE(why.find("body " + std::to_string(reshaped.bodies[first].id) + " has another shape"), std::string::npos)
      << why;
  EXPECT_NE(why.find("materials, contact law settings, gravity"), std::string::npos) << "what may change";
  dem::World moved_wall = pour(2, 40, true);
  moved_wall.planes[1].given_point.x -= 1e-3;
  EXPECT_NE(refused(moved_wall).find("plane wall 1"), std::string::npos);
  dem::World moved_obstacle = pour(2, 40, true);
  std::size_t ell = 0;  // the compound, made fixed and moved a little
  while (moved_obstacle.templates[moved_obstacle.bodies[ell].shape].parts.empty()) ++ell;
  moved_obstacle.bodies[ell].fixed = 1;
  moved_obstacle.bodies[ell].position.x += 1e-3;
  EXPECT_NE(refused(moved_obstacle).find("(fixed) is not where it was"), std::string::npos);
}

// A count that claims more records than the file holds is refused before
// anything is allocated for it (a checksum made to match the damage).
TEST(Checkpoint, HugeCountsAreRefusedWithoutAllocating) {
  dem::World w = pour(2);
  dem::RunState run = dem::plan_run(0.01, 1e-4, 0.01);
  dem::run(w, run, {});
  std::string bytes = encode_checkpoint(w, {run, {}}, 42);
  const std::size_t pair = bytes.rfind("PAIR");  // the section's tag (the INFO text names it too)
  ASSERT_NE(pair, std::string::npos);
  for (int k = 0; k < 8; ++k) bytes[pair + 12 + k] = static_cast<char>(k == 7 ? 0x7f : 0xff);  // count ~ 2^63
  const std::string payload = bytes.substr(40);
  const std::uint64_t sum = fnv1a64(payload);
  for (int k = 0; k < 8; ++k) bytes[24 + k] = static_cast<char>(sum >> (8 * k));
  dem::World t = pour(2);
  EXPECT_NE(refusal(bytes, t).find("count larger than the file"), std::string::npos);
}

}  // namespace
}  // namespace gjkdem::io
