#pragma once
// The per-body quantities as one table: each channel's name, unit,
// components, where a Body holds it (or how it is computed from the world),
// and who takes it. From the rows are made: a checkpoint's BODY section
// (named columns: a reader finds them by name), Python's World views,
// trace.csv's columns, the VTK frames' cell data, the view frames' channel
// block (docs/view-format.md) and the scene export's body keys. A new
// per-body quantity is a member of Body and a row here.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "gjkdem/dem/body.hpp"

namespace gjkdem::dem {

/// Who takes a channel (bits of BodyChannel::use).
enum BodyChannelUse : unsigned {
  kChannelSaved = 1,      ///< a checkpoint's BODY section holds it
  kChannelViewed = 2,     ///< Python's World has a NumPy view of it, under BodyChannel::view
  kChannelWritable = 4,   ///< that view may be written
  kChannelRequired = 8,   ///< a checkpoint without it is refused (the integrator's state)
  kChannelTraced = 16,    ///< trace.csv has it, under BodyChannel::columns
  kChannelVtk = 32,       ///< the VTK frames' cell data have it (single precision)
  kChannelFramed = 64,    ///< the view frames' channel block has it (single precision)
  kChannelExported = 128, ///< the scene export writes it as a free body's key of that name (the scene reader's)
  kChannelLoad = 256,     ///< a load from outside: a world whose view of it is written counts loads (World::applied_loads)
};

struct World;

/// The most components a channel has (a quaternion): writers read a row
/// into a buffer of this many.
inline constexpr std::uint32_t kMaxChannelComponents = 4;
/// The longest channel name (bytes); names are lower case letters, digits
/// and _ (they are file fields and Python names).
inline constexpr std::uint32_t kMaxChannelNameBytes = 64;

/// A channel of reals, `components` of them: in a row from `offset` bytes
/// into a Body, or, for a computed one (`compute` set), worked out from the
/// world (such a channel is only read: never saved, viewed or written).
struct BodyChannel {
  std::string_view name;     ///< as a checkpoint's column, VTK's array, a frame's channel and the export name it
  std::string_view view;     ///< as Python's World names its view (plural)
  std::string_view unit;     ///< SI
  std::uint32_t components;  ///< 3 for a vector, 4 for a quaternion [w, x, y, z]
  std::size_t offset;        ///< offsetof(Body, member); unused by a computed channel
  unsigned use;              ///< BodyChannelUse bits
  std::string_view doc;      ///< what it is (Python's view says it)
  std::string_view columns = {};  ///< trace.csv's column names, comma-separated (kChannelTraced)
  void (*compute)(const World&, const Body&, Real* out) = nullptr;  ///< a computed channel's values
  bool (*present)(const World&) = nullptr;  ///< null: always; else outputs hold it only while true

  Real* in(Body& b) const noexcept { return reinterpret_cast<Real*>(reinterpret_cast<char*>(&b) + offset); }
  const Real* in(const Body& b) const noexcept {
    return reinterpret_cast<const Real*>(reinterpret_cast<const char*>(&b) + offset);
  }
  /// The body's values, `components` of them, into `out`.
  void read(const World& w, const Body& b, Real* out) const noexcept {
    if (compute) return compute(w, b, out);
    for (std::uint32_t k = 0; k < components; ++k) out[k] = in(b)[k];
  }
  bool in_outputs_of(const World& w) const noexcept { return !present || present(w); }
};

inline constexpr unsigned kSavedViewed = kChannelSaved | kChannelViewed;
inline constexpr unsigned kSavedWritable = kChannelSaved | kChannelViewed | kChannelWritable;

/// The computed channels' values and the features' presence tests
/// (src/dem/model/body_channels.cpp).
void frame_orientation_channel(const World& w, const Body& b, Real* out) noexcept;
void angular_velocity_channel(const World& w, const Body& b, Real* out) noexcept;
bool applied_loads_on(const World& w) noexcept;

inline constexpr std::array kBodyChannels{
    BodyChannel{"position", "positions", "m", 3, offsetof(Body, position), kSavedViewed | kChannelRequired | kChannelTraced,
                "Centres of mass (N, 3), read-only view; set_positions changes them.", "x,y,z"},
    BodyChannel{"orientation", "orientations", "1", 4, offsetof(Body, orientation), kSavedViewed | kChannelRequired,
                "Principal frames [w, x, y, z] (N, 4), read-only view; set_orientations changes them."},
    BodyChannel{"frame_orientation", "", "1", 4, 0, kChannelTraced,
                "The orientation of the frame the scene gave the shape in [w, x, y, z]: the principal frame "
                "composed with the template's shape frame.",
                "qw,qx,qy,qz", frame_orientation_channel},
    BodyChannel{"velocity", "velocities", "m/s", 3, offsetof(Body, velocity),
                kSavedWritable | kChannelRequired | kChannelTraced | kChannelVtk | kChannelExported,
                "Velocities of the centres of mass (N, 3), writable view (fixed bodies ignore theirs).", "vx,vy,vz"},
    BodyChannel{"angular_momentum", "angular_momenta", "kg m^2/s", 3, offsetof(Body, angular_momentum),
                kSavedWritable | kChannelRequired,
                "Angular momenta about the centres of mass, world frame (N, 3), writable view: the integrator's "
                "state."},
    BodyChannel{"angular_velocity", "", "rad/s", 3, 0, kChannelTraced | kChannelVtk | kChannelExported,
                "Angular velocities, world frame: the angular momentum through the inverse world inertia.",
                "wx,wy,wz", angular_velocity_channel},
    BodyChannel{"force", "forces", "N", 3, offsetof(Body, force), kSavedViewed | kChannelRequired,
                "Forces of the last evaluation (N, 3), read-only view."},
    BodyChannel{"torque", "torques", "N m", 3, offsetof(Body, torque), kSavedViewed | kChannelRequired,
                "Torques about the centres of mass (N, 3), read-only view."},
    BodyChannel{"applied_force", "applied_forces", "N", 3, offsetof(Body, applied_force),
                kSavedWritable | kChannelFramed | kChannelExported | kChannelLoad,
                "Forces applied from outside (N, 3), writable view: added to every force evaluation from the next "
                "on, until changed (a listener's to set each step: run(listener=...)).",
                {}, nullptr, applied_loads_on},
    BodyChannel{"applied_torque", "applied_torques", "N m", 3, offsetof(Body, applied_torque),
                kSavedWritable | kChannelFramed | kChannelExported | kChannelLoad,
                "Torques applied from outside, about the centres of mass (N, 3), writable view (as applied_forces).",
                {}, nullptr, applied_loads_on},
    BodyChannel{"applied_work", "applied_work", "J", 1, offsetof(Body, applied_work), kSavedViewed,
                "Work the applied loads did on each body so far (N,), read-only view (energies()' applied_work "
                "sums it)."},
};

/// A channel's name as files and Python take it: 1 to kMaxChannelNameBytes
/// lower case letters, digits and _.
constexpr bool channel_name_ok(std::string_view name) noexcept {
  if (name.empty() || name.size() > kMaxChannelNameBytes) return false;
  for (const char ch : name)
    if (!((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_')) return false;
  return true;
}
/// A channel's unit: at most kMaxChannelNameBytes of printable ASCII.
constexpr bool channel_unit_ok(std::string_view unit) noexcept {
  if (unit.size() > kMaxChannelNameBytes) return false;
  for (const char ch : unit)
    if (ch < 0x20 || ch > 0x7e) return false;
  return true;
}

/// Whether the table keeps its own rules: 1 to kMaxChannelComponents
/// components; its name and unit as channel_name_ok and channel_unit_ok
/// say (as the view frames' readers check them); a computed channel is only read; a viewed one names its
/// view; a traced one names its columns and is always present; one name
/// each.
constexpr bool body_channels_well_formed() noexcept {
  for (std::size_t i = 0; i < kBodyChannels.size(); ++i) {
    const BodyChannel& c = kBodyChannels[i];
    if (c.components < 1 || c.components > kMaxChannelComponents) return false;
    if (!channel_name_ok(c.name) || !channel_unit_ok(c.unit)) return false;
    if (c.compute && (c.use & (kChannelSaved | kChannelViewed | kChannelWritable | kChannelRequired))) return false;
    if ((c.use & kChannelViewed) && c.view.empty()) return false;
    if (c.use & kChannelTraced) {  // trace.csv's columns are the same all run: always present
      if (c.present) return false;
      std::size_t commas = 0;
      for (const char ch : c.columns) commas += ch == ',';
      if (c.columns.empty() || commas + 1 != c.components) return false;
    }
    for (std::size_t j = 0; j < i; ++j)
      if (kBodyChannels[j].name == c.name) return false;
  }
  return true;
}
static_assert(body_channels_well_formed(), "kBodyChannels breaks its own rules (see body_channels_well_formed)");

/// The channel named `name`, or null.
constexpr const BodyChannel* find_body_channel(std::string_view name) noexcept {
  for (const BodyChannel& c : kBodyChannels)
    if (c.name == name) return &c;
  return nullptr;
}

}  // namespace gjkdem::dem
