// impulse/narrowphase/detail/manifold_merger.hpp — many small manifolds made
// into few: the triangles a shape touches on a mesh (mesh.hpp), the children
// of a compound (compound.hpp). Manifolds whose normals agree within
// tolerances::same_normal_cosine become one, their points welded (two
// within the weld distance are one, the deeper kept) and reduced to four;
// the deepest few are written out.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <utility>

#include "../../math/quat.hpp"
#include "../manifold.hpp"
#include "../tolerances.hpp"
#include "scratch_buffer.hpp"

namespace impulse::narrowphase::detail {

/// Merges the manifolds of single triangles (or a compound's children)
/// into few: one per normal (within tolerances::same_normal_cosine), at
/// most `capacity`, each reduced to four points once all are in, so that
/// the four do not depend on the order the parts came in (reducing as they
/// come loses a corner: two cubes' four quarters of a face under a bar
/// kept three of its corners and a midpoint). A normal keeps up to
/// `group_points` candidates; past that (a box over more than four
/// triangles) it is reduced to four and goes on. Positions and normals in
/// the working frame.
template <scalar_type T>
class manifold_merger {
 public:
  static constexpr std::size_t capacity = 16;
  static constexpr std::size_t group_points = 16;

  explicit manifold_merger(T weld) noexcept : weld_squared_(weld * weld), points_(capacity * group_points) {}
  manifold_merger(const manifold_merger&) = delete;
  manifold_merger& operator=(const manifold_merger&) = delete;

  void add(const contact_manifold<T>& m) noexcept {
    if (m.empty()) return;
    for (std::size_t g = 0; g < count_; ++g) {
      if (dot(groups_[g].normal, m.normal) <= tolerances<T>::same_normal_cosine) continue;
      groups_[g].single = false;
      for (const contact_point<T>& p : m.contacts()) add_point(g, p);
      return;
    }
    std::size_t g = count_;
    if (count_ < capacity) {
      ++count_;
    } else {
      // Full (a shape touching more than 16 differently turned faces at
      // once): the new one replaces the shallowest if it is deeper.
      g = 0;
      for (std::size_t k = 1; k < count_; ++k)
        if (groups_[k].deepest < groups_[g].deepest) g = k;
      if (!(deepest(m) > groups_[g].deepest)) return;
    }
    groups_[g] = {m.normal, 0, -std::numeric_limits<T>::infinity(), true};
    for (const contact_point<T>& p : m.contacts()) add_point(g, p);
  }

  /// Writes the deepest min(out.size(), count) manifolds to out, deepest
  /// first, carried to world space by `to_world` (a point map) and
  /// `rotation` (the working frame's axes in world). Returns how many.
  template <class ToWorld>
  std::size_t write(std::span<contact_manifold<T>> out, const quat<T>& rotation, ToWorld&& to_world,
                    bool flip) noexcept {
    std::array<std::size_t, capacity> order;
    for (std::size_t g = 0; g < count_; ++g) order[g] = g;
    // Insertion sort, deepest first, equals in the order found: at most 16,
    // and std::stable_sort may allocate.
    for (std::size_t i = 1; i < count_; ++i)
      for (std::size_t j = i; j > 0 && groups_[order[j]].deepest > groups_[order[j - 1]].deepest; --j)
        std::swap(order[j], order[j - 1]);
    const std::size_t written = std::min(out.size(), count_);
    for (std::size_t i = 0; i < written; ++i) {
      contact_manifold<T> m;
      reduced(order[i], m);
      m.normal = rotate(rotation, m.normal);
      for (int k = 0; k < m.count; ++k) m.points[std::size_t(k)].position = to_world(m.points[std::size_t(k)].position);
      out[i] = flip ? m.flipped() : m;
    }
    return written;
  }

 private:
  /// Keeps at most four of the n candidates in `group`. Points along one
  /// line (a capsule lying across several triangles, within 1e-3 of the
  /// line's length of it) keep the line's two ends, and the deepest point
  /// if it is deeper than both by the weld distance (a line over a bent
  /// mesh); else reduce_to_four. (reduce_to_four's own line case keeps the
  /// deepest point whatever its depth; here the welded duplicates from
  /// neighbouring triangles would make it keep a third point of the same
  /// depth.)
  void reduce(const contact_point<T>* candidates, std::size_t n, contact_manifold<T>& group) const noexcept {
    const vec3<T> normal = group.normal;
    const auto across = [&](const vec3<T>& d) { return d - normal * dot(d, normal); };
    std::size_t e0 = 0, e1 = 0, deepest_point = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (length_squared(across(candidates[i].position - candidates[0].position)) >
          length_squared(across(candidates[e0].position - candidates[0].position)))
        e0 = i;
    for (std::size_t i = 0; i < n; ++i) {
      if (length_squared(across(candidates[i].position - candidates[e0].position)) >
          length_squared(across(candidates[e1].position - candidates[e0].position)))
        e1 = i;
      if (candidates[i].depth > candidates[deepest_point].depth) deepest_point = i;
    }
    const vec3<T> line = across(candidates[e1].position - candidates[e0].position);
    const T length2 = length_squared(line);
    bool straight = n > 2 && length2 > weld_squared_;
    for (std::size_t i = 0; i < n && straight; ++i) {
      // Twice the area of e0, e1, i over the line's length: i's distance from the line.
      const T twice_area2 = length_squared(cross(line, across(candidates[i].position - candidates[e0].position)));
      straight = twice_area2 <= tolerances<T>::collinear_fraction_squared * length2 * length2;
    }
    if (!straight) {
      contact_point<T> kept[group_points];
      const std::size_t k = outline(candidates, n, normal, kept);
      reduce_to_four(std::span<const contact_point<T>>(kept, k), normal, group);
      return;
    }
    group.count = 0;
    group.add(candidates[e0]);
    group.add(candidates[e1]);
    const contact_point<T>& d = candidates[deepest_point];
    if (d.depth > std::max(candidates[e0].depth, candidates[e1].depth) + std::sqrt(weld_squared_)) group.add(d);
  }

  /// Of the n candidates (n ≤ group_points), those that can matter, into
  /// `out`; returns how many. The corners of their outline across the normal
  /// (Andrew's monotone chain; points on an edge of it, within
  /// collinear_fraction of its size, are not corners), and any point deeper
  /// than every corner by more than the weld distance (a bump under a
  /// face). A face over several parts has points along the parts' seams,
  /// on its outline's edges or inside it; reduce_to_four, which starts from
  /// the deepest, would start from one of them when rounding made it the
  /// deepest, and lose a corner: a pair test of the whole face has none.
  std::size_t outline(const contact_point<T>* in, std::size_t n, const vec3<T>& normal,
                      contact_point<T>* out) const noexcept {
    const vec3<T> u = normalize_or(cross(normal, std::abs(normal.x) < T(0.6) ? vec3<T>::unit_x() : vec3<T>::unit_y()),
                                   vec3<T>::unit_z());
    const vec3<T> v = cross(normal, u);
    T x[group_points], y[group_points];
    std::size_t order[group_points];
    T lo_x = std::numeric_limits<T>::infinity(), hi_x = -lo_x, lo_y = lo_x, hi_y = hi_x;
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = dot(in[i].position, u), y[i] = dot(in[i].position, v);
      lo_x = std::min(lo_x, x[i]), hi_x = std::max(hi_x, x[i]);
      lo_y = std::min(lo_y, y[i]), hi_y = std::max(hi_y, y[i]);
      std::size_t j = i;  // insertion sort by (x, y): at most 16
      for (; j > 0 && (x[order[j - 1]] > x[i] || (x[order[j - 1]] == x[i] && y[order[j - 1]] > y[i])); --j)
        order[j] = order[j - 1];
      order[j] = i;
    }
    // A turn o → a → b counts as one only if b is off the line oa by more
    // than collinear_fraction of the candidates' spread.
    const T spread2 = (hi_x - lo_x) * (hi_x - lo_x) + (hi_y - lo_y) * (hi_y - lo_y);
    const T least = tolerances<T>::collinear_fraction * spread2;
    const auto left_turn = [&](std::size_t o, std::size_t a, std::size_t b) {
      return (x[a] - x[o]) * (y[b] - y[o]) - (y[a] - y[o]) * (x[b] - x[o]) > least;
    };
    std::size_t hull[2 * group_points];
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {  // lower chain
      while (k >= 2 && !left_turn(hull[k - 2], hull[k - 1], order[i])) --k;
      hull[k++] = order[i];
    }
    for (std::size_t i = n - 1, lower = k + 1; i-- > 0;) {  // upper chain
      while (k >= lower && !left_turn(hull[k - 2], hull[k - 1], order[i])) --k;
      hull[k++] = order[i];
    }
    if (k < 4) {  // fewer than three corners: no outline to speak of
      for (std::size_t i = 0; i < n; ++i) out[i] = in[i];
      return n;
    }
    --k;  // the chain ends where it began
    bool corner[group_points] = {};
    T corner_depth = -std::numeric_limits<T>::infinity();
    for (std::size_t i = 0; i < k; ++i) {
      corner[hull[i]] = true;
      corner_depth = std::max(corner_depth, in[hull[i]].depth);
    }
    std::size_t m = 0;
    const T weld = std::sqrt(weld_squared_);
    for (std::size_t i = 0; i < n; ++i)
      if (corner[i] || in[i].depth > corner_depth + weld) out[m++] = in[i];
    return m;
  }

  static T deepest(const contact_manifold<T>& m) noexcept {
    T d = -std::numeric_limits<T>::infinity();
    for (const contact_point<T>& p : m.contacts()) d = std::max(d, p.depth);
    return d;
  }

  /// Group g's candidates, reduced to a manifold. A group made of one
  /// manifold is that manifold, as its pair test gave it.
  void reduced(std::size_t g, contact_manifold<T>& m) const noexcept {
    const group& in = groups_[g];
    const contact_point<T>* candidates = points_.data() + g * group_points;
    m.normal = in.normal;
    m.count = 0;
    if (in.single && in.count <= std::size_t(contact_manifold<T>::capacity)) {
      for (std::size_t i = 0; i < in.count; ++i) m.add(candidates[i]);
      return;
    }
    reduce(candidates, in.count, m);
  }

  /// p into group g: welded to a candidate within the weld distance (the
  /// deeper kept), else added; a full group is reduced to four first.
  void add_point(std::size_t g, const contact_point<T>& p) noexcept {
    group& in = groups_[g];
    contact_point<T>* candidates = points_.data() + g * group_points;
    in.deepest = std::max(in.deepest, p.depth);
    for (std::size_t i = 0; i < in.count; ++i) {
      if (length_squared(candidates[i].position - p.position) > weld_squared_) continue;
      if (p.depth > candidates[i].depth) candidates[i] = p;
      return;
    }
    if (in.count == group_points) {
      contact_manifold<T> four;
      four.normal = in.normal;
      reduce(candidates, in.count, four);
      in.count = 0;
      for (const contact_point<T>& kept : four.contacts()) candidates[in.count++] = kept;
    }
    candidates[in.count++] = p;
  }

  struct group {
    vec3<T> normal;
    std::size_t count;  ///< candidates in points_[g·group_points …]
    T deepest;          ///< m: the deepest candidate's depth
    bool single;        ///< made of one manifold
  };
  std::array<group, capacity> groups_;
  std::size_t count_ = 0;
  T weld_squared_;
  /// The candidates, group_points per group, left unwritten until used.
  scratch_buffer<contact_point<T>, capacity * group_points> points_;
};

}  // namespace impulse::narrowphase::detail
