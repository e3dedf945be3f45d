// contact_force (contact_force.hpp) against forces worked out by hand from
// the laws docs/dem.md states, for each law, on one contact of known
// geometry (no damping, so every term is a closed form):
// - Hertz: F = 4/3 E* sqrt(R*) d^1.5, energy 8/15 E* sqrt(R*) d^2.5; Mindlin's
//   tangential spring 8 G* sqrt(R* d) on the slip v dt, capped at mu F;
// - linear: F = E* R* d, energy k d^2 / 2, the tangential spring 2/7 k;
// - volume, normalized form: F = (E*/R*) A d; potential form: times A / a_ref^2
//   (a_ref^3 the smaller volume), energy k V^2 / (2 a_ref^2); a plane wall's
//   energy k times the depth integral; twisting k_t r^2 / 2 (r^2 = A / pi)
//   capped at 2/3 mu F r; rocking k r^2 / 4 between bodies, none on a plane;
// - rolling friction 2.25 k (mu_r R*)^2 capped at mu_r R* F;
// - the torque on b: the normal force's moment, the point's arm of friction,
//   the couples.
#include "gjkdem/dem/contact_force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace gjkdem::dem {
namespace {

constexpr Real kE = 2e7, kG = 8e6, kR = 0.01, kDepth = 1e-4, kArea = 3e-5, kVolume = 2e-9;
constexpr Real kMass = 0.02, kBodyVolume = 8e-6, kDt = 1e-5;

ContactGeometry geometry() {
  ContactGeometry g;
  g.status = GeometryStatus::Touching;
  g.normal = {0, 0, 1};
  g.point = {0.001, 0, 0.002};
  g.depth = kDepth;
  g.area = kArea;
  g.volume = kVolume;
  g.depth_integral = 3e-13;
  g.moment = {0.004, -0.001, 0};
  return g;
}

MaterialPair materials(Real friction, Real rolling = 0) {
  return {.youngs_modulus = kE, .shear_modulus = kG, .friction = friction, .restitution = 1,
          .rolling_friction = rolling, .rolling_damping = 0, .damping = 0};
}

// A body whose centre is at the contact point (a spin slides nothing there).
ContactSide side(Vec3 velocity = {}, Vec3 spin = {}) {
  return {.moving = true, .position = geometry().point, .velocity = velocity, .spin = spin, .mass = kMass,
          .curvature_radius = 2 * kR, .volume = kBodyVolume};  // R* = kR for two alike
}

// A plane wall: infinite mass, curvature radius and volume (R* = 2 kR against a body).
ContactSide wall() {
  constexpr Real inf = std::numeric_limits<Real>::infinity();
  return {.moving = false, .position = {}, .velocity = {}, .spin = {}, .mass = inf, .curvature_radius = inf,
          .volume = inf};
}

WorldSettings law(ContactModel model, VolumeForm form = VolumeForm::Normalized, bool rocking = false) {
  WorldSettings s;
  s.model = model;
  s.volume_form = form;
  s.rocking_resistance = rocking;
  return s;
}

void expect_vec(const Vec3& got, const Vec3& want, Real scale) {
  EXPECT_NEAR(got.x, want.x, 1e-12 * scale);
  EXPECT_NEAR(got.y, want.y, 1e-12 * scale);
  EXPECT_NEAR(got.z, want.z, 1e-12 * scale);
}

TEST(ContactForce, HertzNormalForceEnergyAndMindlinsSpring) {
  const ContactGeometry g = geometry();
  const Real f = 4.0 / 3 * kE * std::sqrt(kR) * std::pow(kDepth, 1.5);
  const Real k_t = 8 * kG * std::sqrt(kR * kDepth);
  const Real v = 0.01;  // b slides along x: the spring stretches by v dt, below the cap
  const ContactForce out = contact_force(g, false, materials(0.5), side(), side({v, 0, 0}), {}, law(ContactModel::Hertz), kDt);
  const Vec3 ft{-k_t * v * kDt, 0, 0};
  ASSERT_LT(std::fabs(ft.x), 0.5 * f);
  expect_vec(out.force, Vec3{0, 0, f} + ft, f);
  expect_vec(out.torque, g.moment * f + cross(g.point, ft), f * 0.01);
  expect_vec(out.history.spring, {v * kDt, 0, 0}, v * kDt);
  const Real energy = 8.0 / 15 * kE * std::sqrt(kR) * std::pow(kDepth, 2.5) + 0.5 * k_t * (v * kDt) * (v * kDt);
  EXPECT_NEAR(out.elastic, energy, 1e-12 * energy);
}

TEST(ContactForce, SlidingIsCappedAtCoulombsLimitAndTheSpringKeepsWhatHoldsIt) {
  const ContactGeometry g = geometry();
  const Real f = 4.0 / 3 * kE * std::sqrt(kR) * std::pow(kDepth, 1.5);
  const Real k_t = 8 * kG * std::sqrt(kR * kDepth);
  const Real mu = 0.3;
  const ContactForce out =
      contact_force(g, false, materials(mu), side(), side({0, 5, 0}), {}, law(ContactModel::Hertz), kDt);
  expect_vec(out.force, {0, -mu * f, f}, f);
  expect_vec(out.history.spring, {0, mu * f / k_t, 0}, mu * f / k_t);
}

TEST(ContactForce, LinearLawForceEnergyAndSpring) {
  const ContactGeometry g = geometry();
  const Real k = kE * kR, f = k * kDepth, k_t = 2.0 / 7 * k;
  const Vec3 spring_before{2e-7, 0, 0};  // carried in from the last step
  const ContactForce out = contact_force(g, false, materials(0.8), side(), side(), PairHistory{.spring = spring_before, .twist = 0, .roll = {}},
                                         law(ContactModel::Linear), kDt);
  expect_vec(out.force, {-k_t * 2e-7, 0, f}, f);
  EXPECT_NEAR(out.elastic, 0.5 * k * kDepth * kDepth + 0.5 * k_t * 4e-14, 1e-12 * f * kDepth);
}

TEST(ContactForce, VolumeLawNormalizedAndPotentialForms) {
  const ContactGeometry g = geometry();
  const Real k_volume = kE / kR;
  const ContactForce flat =
      contact_force(g, false, materials(0), side(), side(), {}, law(ContactModel::Volume), kDt);
  const Real f = k_volume * kArea * kDepth;
  expect_vec(flat.force, {0, 0, f}, f);
  EXPECT_NEAR(flat.elastic, 0.5 * k_volume * kArea * kDepth * kDepth, 1e-12 * f * kDepth);
  const ContactForce potential = contact_force(g, false, materials(0), side(), side(), {},
                                               law(ContactModel::Volume, VolumeForm::Potential), kDt);
  const Real a_ref2 = std::pow(std::cbrt(kBodyVolume), 2);
  const Real fp = k_volume * kArea * kArea / a_ref2 * kDepth;
  expect_vec(potential.force, {0, 0, fp}, fp);
  EXPECT_NEAR(potential.elastic, 0.5 * k_volume * kVolume * kVolume / a_ref2, 1e-12 * fp * kDepth);
  // Against a plane wall (R* twice as large): the depth integral's energy.
  const Real k_plane = kE / (2 * kR);
  const ContactForce plane = contact_force(g, true, materials(0), wall(), side(), {}, law(ContactModel::Volume), kDt);
  expect_vec(plane.force, {0, 0, k_plane * kArea * kDepth}, f);
  EXPECT_NEAR(plane.elastic, k_plane * g.depth_integral, 1e-12 * k_plane * g.depth_integral);
}

TEST(ContactForce, VolumeLawTwistingAndRockingOfTheContactArea) {
  const ContactGeometry g = geometry();
  const Real k = kE / kR * kArea, f = k * kDepth, k_t = 2.0 / 7 * k, r2 = kArea / kPi;
  const Real w = 2.0;  // b spins about the normal, and rocks about x
  const ContactForce twist = contact_force(g, false, materials(0.5), side(), side({}, {0, 0, w}), {},
                                           law(ContactModel::Volume), kDt);
  const Real couple = -k_t * r2 / 2 * w * kDt;
  ASSERT_LT(std::fabs(couple), 2.0 / 3 * 0.5 * f * std::sqrt(r2));
  expect_vec(twist.torque, g.moment * f + Vec3{0, 0, couple}, f * 0.01);
  EXPECT_NEAR(twist.history.twist, w * kDt, 1e-15);
  // Rocking between bodies (rocking_resistance), none against a plane wall.
  const ContactForce rock = contact_force(g, false, materials(0), side(), side({}, {w, 0, 0}), {},
                                          law(ContactModel::Volume, VolumeForm::Normalized, true), kDt);
  expect_vec(rock.torque, g.moment * f + Vec3{-k * r2 / 4 * w * kDt, 0, 0}, f * 0.01);
  const ContactForce on_plane = contact_force(g, true, materials(0), wall(), side({}, {w, 0, 0}), {},
                                              law(ContactModel::Volume, VolumeForm::Normalized, true), kDt);
  expect_vec(on_plane.torque, g.moment * (f / 2), f * 0.01);  // k on a plane: E* / (2 kR)
}

TEST(ContactForce, RollingFrictionSpringAndItsCap) {
  const ContactGeometry g = geometry();
  const Real k = kE * kR, f = k * kDepth, mu_r = 0.02;
  const Real k_roll = 2.25 * k * (mu_r * kR) * (mu_r * kR);
  const Real w = 3.0;
  const ContactForce slow = contact_force(g, false, materials(0, mu_r), side(), side({}, {0, w, 0}), {},
                                          law(ContactModel::Linear), kDt);
  ASSERT_LT(k_roll * w * kDt, mu_r * kR * f);
  expect_vec(slow.torque, g.moment * f + Vec3{0, -k_roll * w * kDt, 0}, f * 0.01);
  EXPECT_NEAR(slow.history.roll.y, w * kDt, 1e-15);
  // A roll of a whole radian: past the cap, the couple is mu_r R* F.
  const ContactForce capped = contact_force(g, false, materials(0, mu_r), side(), side(), PairHistory{.spring = {}, .twist = 0, .roll = {0, 1, 0}},
                                            law(ContactModel::Linear), kDt);
  expect_vec(capped.torque, g.moment * f + Vec3{0, -mu_r * kR * f, 0}, f * 0.01);
}

TEST(ContactForce, ApartOrUntouchedMeansNoForce) {
  ContactGeometry g = geometry();
  g.depth = 0;
  for (ContactModel model : {ContactModel::Hertz, ContactModel::Linear}) {
    const ContactForce out = contact_force(g, false, materials(0.5), side(), side({1, 0, 0}), {}, law(model), kDt);
    EXPECT_EQ(out.force, Vec3{});
  }
}

}  // namespace
}  // namespace gjkdem::dem
