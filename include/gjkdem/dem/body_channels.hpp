#pragma once
// The per-body quantities as one table: each channel's name, unit,
// components, where a Body holds it, and who takes it. A checkpoint's BODY
// section is made from the saved rows (named columns: a reader finds them
// by name), Python's World views from the viewed ones. A new per-body
// quantity is a member of Body and a row here.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "gjkdem/dem/body.hpp"

namespace gjkdem::dem {

/// Who takes a channel (bits of BodyChannel::use).
enum BodyChannelUse : unsigned {
  kChannelSaved = 1,     ///< a checkpoint's BODY section holds it
  kChannelViewed = 2,    ///< Python's World has a NumPy view of it, under BodyChannel::view
  kChannelWritable = 4,  ///< that view may be written
  kChannelRequired = 8,  ///< a checkpoint without it is refused (the integrator's state)
};

/// A channel of reals, `components` of them in a row from `offset` bytes
/// into a Body.
struct BodyChannel {
  std::string_view name;     ///< as a checkpoint's column names it
  std::string_view view;     ///< as Python's World names its view (plural)
  std::string_view unit;     ///< SI
  std::uint32_t components;  ///< 3 for a vector, 4 for a quaternion [w, x, y, z]
  std::size_t offset;        ///< offsetof(Body, member)
  unsigned use;              ///< BodyChannelUse bits
  std::string_view doc;      ///< what it is (Python's view says it)

  Real* in(Body& b) const noexcept { return reinterpret_cast<Real*>(reinterpret_cast<char*>(&b) + offset); }
  const Real* in(const Body& b) const noexcept {
    return reinterpret_cast<const Real*>(reinterpret_cast<const char*>(&b) + offset);
  }
};

inline constexpr unsigned kSavedViewed = kChannelSaved | kChannelViewed;
inline constexpr unsigned kSavedWritable = kChannelSaved | kChannelViewed | kChannelWritable;
inline constexpr unsigned kState = kChannelRequired;

inline constexpr std::array kBodyChannels{
    BodyChannel{"position", "positions", "m", 3, offsetof(Body, position), kSavedViewed | kState,
                "Centres of mass (N, 3), read-only view; set_positions changes them."},
    BodyChannel{"orientation", "orientations", "1", 4, offsetof(Body, orientation), kSavedViewed | kState,
                "Principal frames [w, x, y, z] (N, 4), read-only view; set_orientations changes them."},
    BodyChannel{"velocity", "velocities", "m/s", 3, offsetof(Body, velocity), kSavedWritable | kState,
                "Velocities of the centres of mass (N, 3), writable view (fixed bodies ignore theirs)."},
    BodyChannel{"angular_momentum", "angular_momenta", "kg m^2/s", 3, offsetof(Body, angular_momentum),
                kSavedWritable | kState,
                "Angular momenta about the centres of mass, world frame (N, 3), writable view: the integrator's "
                "state."},
    BodyChannel{"force", "forces", "N", 3, offsetof(Body, force), kSavedViewed | kState,
                "Forces of the last evaluation (N, 3), read-only view."},
    BodyChannel{"torque", "torques", "N m", 3, offsetof(Body, torque), kSavedViewed | kState,
                "Torques about the centres of mass (N, 3), read-only view."},
    BodyChannel{"applied_force", "applied_forces", "N", 3, offsetof(Body, applied_force), kSavedWritable,
                "Forces applied from outside (N, 3), writable view: added to every force evaluation from the next "
                "on, until changed (a listener's to set each step: run(listener=...))."},
    BodyChannel{"applied_torque", "applied_torques", "N m", 3, offsetof(Body, applied_torque), kSavedWritable,
                "Torques applied from outside, about the centres of mass (N, 3), writable view (as applied_forces)."},
    BodyChannel{"applied_work", "applied_work", "J", 1, offsetof(Body, applied_work), kSavedViewed,
                "Work the applied loads did on each body so far (N,), read-only view (energies()' applied_work "
                "sums it)."},
};

/// The channel named `name`, or null.
constexpr const BodyChannel* find_body_channel(std::string_view name) noexcept {
  for (const BodyChannel& c : kBodyChannels)
    if (c.name == name) return &c;
  return nullptr;
}

}  // namespace gjkdem::dem
