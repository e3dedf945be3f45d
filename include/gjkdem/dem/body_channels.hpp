#pragma once
// The per-body quantities as one table: each channel's name, unit,
// components, where a Body holds it (or how it is computed from the world),
// and who takes it. From the rows are made: a checkpoint's BODY section
// (named columns: a reader finds them by name), Python's World views,
// trace.csv's columns, the VTK frames' cell data, the view frames' channel
// block (docs/view-format.md) and the scene export's body keys. A new
// per-body quantity is a row of body_channel_rows.hpp, which makes both the
// Body member and the channel.
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
  kChannelGiven = 512,    ///< a scene's [[body]] (BodyDef::given) may give its value, placed as given (a free body's, for a load)
};

/// What each fragment of a split grain takes of the grain's value.
enum class ChannelSplit : std::uint8_t {
  Kinematic,  ///< the split's own: the fragment's place and motion (split_body.hpp)
  Zeroed,     ///< nothing: the last evaluation's, found again for the fragments
  ByMass,     ///< its share by mass (an extensive quantity: a load, a work)
  Copied,     ///< the same value (an intensive quantity: a temperature)
};

/// How many reals a channel of type T has (Real, Vec3, Quat).
template <class T>
constexpr std::uint32_t components_of() noexcept {
  static_assert(sizeof(T) % sizeof(Real) == 0 && alignof(T) == alignof(Real), "a channel is a row of reals");
  return static_cast<std::uint32_t>(sizeof(T) / sizeof(Real));
}

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
  ChannelSplit split = ChannelSplit::Copied;  ///< a held channel's: what a fragment takes (apply_splits)

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

#define GJKDEM_HELD_CHANNEL(name_, Type, view_, unit_, use_, split_, present_, doc_, columns_)                       \
  BodyChannel{#name_, view_, unit_, components_of<Type>(), offsetof(Body, name_), use_, doc_, columns_, nullptr, \
              present_, ChannelSplit::split_},
#define GJKDEM_COMPUTED_CHANNEL(name_, Type, unit_, use_, doc_, columns_, compute_) \
  BodyChannel{#name_, "", unit_, components_of<Type>(), 0, use_, doc_, columns_, compute_},
/// The table, made from body_channel_rows.hpp in its order.
inline constexpr std::array kBodyChannels{GJKDEM_BODY_CHANNEL_ROWS(GJKDEM_HELD_CHANNEL, GJKDEM_COMPUTED_CHANNEL)};
#undef GJKDEM_HELD_CHANNEL
#undef GJKDEM_COMPUTED_CHANNEL

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
/// view; a traced one names its columns and is always present; a given one
/// is held and exported; the kinematic ones are the four a split sets; one
/// name each.
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
    // A given channel is held and exported (an exported scene gives it back).
    if ((c.use & kChannelGiven) && (c.compute || !(c.use & kChannelExported))) return false;
    // apply_splits sets the kinematic ones itself: the place and the motion.
    const bool kinematic = !c.compute && c.split == ChannelSplit::Kinematic;
    const bool moves = c.name == "position" || c.name == "orientation" || c.name == "velocity" ||
                       c.name == "angular_momentum";
    if (kinematic != moves) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (kBodyChannels[j].name == c.name) return false;
  }
  return true;
}
static_assert(body_channels_well_formed(), "kBodyChannels breaks its own rules (see body_channels_well_formed)");

/// A value a scene gives one of a body's channels (kChannelGiven rows):
/// the builder places it on the body as it is.
struct GivenChannel {
  const BodyChannel* channel = nullptr;  ///< into kBodyChannels
  std::array<Real, kMaxChannelComponents> values{};  ///< its first `components`
};

/// The channel named `name`, or null.
constexpr const BodyChannel* find_body_channel(std::string_view name) noexcept {
  for (const BodyChannel& c : kBodyChannels)
    if (c.name == name) return &c;
  return nullptr;
}

}  // namespace gjkdem::dem
