#pragma once
// The rows of the body channel table (body_channels.hpp), the one place a
// per-body quantity is declared: its row makes the Body member that holds
// it (body.hpp) and its channel, from which the checkpoint, Python's views,
// trace.csv, the VTK and view frames, the scene reader and export, and the
// fragments of a split take it. A new per-body quantity is one row here.
//
// A list macro (an "X macro", as MuJoCo's mjxmacro.h declares mjData's
// arrays) because a row must make both a member of a plain struct and a
// table entry holding its offset, and C++ has no other way to make members
// from a list. The macro is expanded twice, in body.hpp and in
// body_channels.hpp; its arguments are read only there.
//
// HELD(name, Type, view, unit, use, split, present, doc, columns): a channel
//   held by Body as `Type name` (Real, Vec3 or Quat), in row order.
//   view: Python's World names its view so (plural; "" for none).
//   unit: SI. use: BodyChannelUse bits. split: ChannelSplit, what a
//   fragment takes of its grain's value. present: null (always), or a test
//   of the world that outputs hold it only while true. doc: what it is
//   (Python's view says it). columns: trace.csv's (kChannelTraced).
// COMPUTED(name, Type, unit, use, doc, columns, compute): a channel worked
//   out from the world by `compute` (body_channels.cpp), only read.
//
// Rows appear in outputs in this order (trace.csv's columns, the frames'
// channels, the checkpoint's columns): a new row goes last to keep theirs,
// above the closing comment, so that adding it changes no other line.
#define GJKDEM_BODY_CHANNEL_ROWS(HELD, COMPUTED)                                                                      \
  HELD(position, Vec3, "positions", "m", kSavedViewed | kChannelRequired | kChannelTraced, Kinematic, nullptr,        \
       "Centres of mass (N, 3), read-only view; set_positions changes them.", "x,y,z")                                 \
  HELD(orientation, Quat, "orientations", "1", kSavedViewed | kChannelRequired, Kinematic, nullptr,                   \
       "Principal frames [w, x, y, z] (N, 4), read-only view; set_orientations changes them.", "")                     \
  COMPUTED(frame_orientation, Quat, "1", kChannelTraced,                                                             \
           "The orientation of the frame the scene gave the shape in [w, x, y, z]: the principal frame "               \
           "composed with the template's shape frame.",                                                                \
           "qw,qx,qy,qz", frame_orientation_channel)                                                                   \
  HELD(velocity, Vec3, "velocities", "m/s",                                                                            \
       kSavedWritable | kChannelRequired | kChannelTraced | kChannelVtk | kChannelExported, Kinematic, nullptr,        \
       "Velocities of the centres of mass (N, 3), writable view (fixed bodies ignore theirs).", "vx,vy,vz")            \
  HELD(angular_momentum, Vec3, "angular_momenta", "kg m^2/s", kSavedWritable | kChannelRequired, Kinematic, nullptr, \
       "Angular momenta about the centres of mass, world frame (N, 3), writable view: the integrator's state.", "")   \
  COMPUTED(angular_velocity, Vec3, "rad/s", kChannelTraced | kChannelVtk | kChannelExported,                         \
           "Angular velocities, world frame: the angular momentum through the inverse world inertia.", "wx,wy,wz",    \
           angular_velocity_channel)                                                                                   \
  HELD(force, Vec3, "forces", "N", kSavedViewed | kChannelRequired, Zeroed, nullptr,                                   \
       "Forces of the last evaluation (N, 3), read-only view.", "")                                                   \
  HELD(torque, Vec3, "torques", "N m", kSavedViewed | kChannelRequired, Zeroed, nullptr,                              \
       "Torques about the centres of mass (N, 3), read-only view.", "")                                              \
  HELD(applied_force, Vec3, "applied_forces", "N",                                                                     \
       kSavedWritable | kChannelFramed | kChannelGiven | kChannelExported | kChannelLoad, ByMass, applied_loads_on,    \
       "Forces applied from outside (N, 3), writable view: added to every force evaluation from the next on, until "  \
       "changed (a listener's to set each step: run(listener=...)).",                                                  \
       "")                                                                                                             \
  HELD(applied_torque, Vec3, "applied_torques", "N m",                                                                 \
       kSavedWritable | kChannelFramed | kChannelGiven | kChannelExported | kChannelLoad, ByMass, applied_loads_on,    \
       "Torques applied from outside, about the centres of mass (N, 3), writable view (as applied_forces).", "")      \
  HELD(applied_work, Real, "applied_work", "J", kSavedViewed, ByMass, nullptr,                                         \
       "Work the applied loads did on each body so far (N,), read-only view (energies()' applied_work sums it).", "") \
  /* the end of the rows: a new row goes above this line */
