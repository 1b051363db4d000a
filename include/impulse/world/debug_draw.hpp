// impulse/world/debug_draw.hpp — what a world can draw, and what it draws
// with.
//
// A world draws through any type with three calls, `line(a, b, color)`,
// `point(p, color)` and `arrow(from, to, color)`, in world coordinates
// (metres): an OpenGL line renderer, an SVG writer or a test's recorder.
// It never allocates or keeps the drawer.
#pragma once

#include "../math/vec3.hpp"

namespace impulse {

struct debug_color {
  float r = 1, g = 1, b = 1;  ///< each in [0, 1]
};

/// What world::draw shows.
struct debug_draw_flags {
  /// Each body's shape as a wireframe, in its body's colour (detail/
  /// debug_drawing.hpp): a sphere's three great circles, a box's and a
  /// hull's edges, a capsule's rings, caps and sides, a mesh's triangles,
  /// a plane's 10 m square and normal; sensors in yellow.
  bool shapes = true;
  /// Each joint: its anchors on A and B, lines from each body's center to
  /// its anchor, a hinge's or slider's axis, and its limits (a hinge's
  /// arc, a slider's span along its axis).
  bool joints = true;
  bool aabbs = false;       ///< each body's bounding box (as the broad phase has it, before the speculative margin)
  bool contacts = true;     ///< contact points
  bool normals = true;      ///< contact normals, 0.2 m long
  bool velocities = false;  ///< each dynamic body's velocity, drawn as the step it makes in 0.1 s
  bool forces = false;      ///< each contact point's last impulse divided by dt, at 0.01 m per newton
};

template <class D, class T>
concept debug_drawer = requires(D& d, const vec3<T>& p, const debug_color& c) {
  d.line(p, p, c);
  d.point(p, c);
  d.arrow(p, p, c);
};

}  // namespace impulse
