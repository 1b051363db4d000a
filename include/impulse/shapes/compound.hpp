// impulse/shapes/compound.hpp — one body made of several convex shapes.
//
// A chair, a dumbbell, an L-shaped beam, a table: shapes that are not
// convex, built from convex children (spheres, boxes, capsules, hulls),
// each at its own pose in the compound's frame, as Jolt's StaticCompound
// and Bullet's btCompoundShape do. The body moves as one rigid piece:
//
// - mass properties are the exact sum of the children's (each child's
//   closed form, carried to the compound's frame by the parallel-axis
//   theorem: mass_properties.hpp), with an optional density per child
//   relative to the body's material;
// - the narrow phase tests each child near the other shape
//   (narrowphase/compound.hpp), found through a tree over the children's
//   boxes (detail/triangle_bvh.hpp, the mesh's tree), and merges the
//   children's manifolds by normal, so that two boxes side by side rest
//   on a floor with one manifold of four corners, as the hull around them
//   would; each point's feature id carries its child's index, so the same
//   child's same features keep their id from step to step (warm starting);
// - ray casts, shape casts and continuous collision go child by child.
//
// Built once by a builder and then immutable, like a hull or a mesh: a
// world copies the compound it is given.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/policy.hpp"
#include "../math/aabb.hpp"
#include "../math/quat.hpp"
#include "../math/transform.hpp"
#include "box.hpp"
#include "capsule.hpp"
#include "convex_hull.hpp"
#include "detail/thinnest_half_extent.hpp"
#include "detail/triangle_bvh.hpp"
#include "mass_properties.hpp"
#include "sphere.hpp"

namespace impulse {

/// Which convex shape a child of a compound is.
enum class compound_part : std::uint8_t { sphere, box, capsule, convex_hull };

template <scalar_type T>
class compound_builder;

template <scalar_type T>
class compound {
 public:
  static constexpr policy_kind kind = policy_kind::shape;
  /// The most children a compound takes (feature ids keep 16 bits for the
  /// child's index: narrowphase/compound.hpp).
  static constexpr std::size_t max_children = 1u << 16;

  /// One child: where it is in the compound's frame, its box there, and its
  /// density relative to the body's material.
  struct child {
    transform<T> pose = transform<T>::identity();
    aabb<T> bounds{};
    T relative_density = T(1);
    compound_part part = compound_part::sphere;
    std::uint32_t slot = 0;  ///< place in its part's array
  };

  /// Collects the children; build() makes the compound.
  using builder = compound_builder<T>;

  /// Refuses a compound with no children (moved from): builder::build never
  /// makes one. The world checks every shape it is given this way.
  void validate() const {
    if (children_.empty())
      detail::report_error(error_code::degenerate_shape, "compound: the compound is empty (moved from); use a builder");
  }

  [[nodiscard]] std::size_t child_count() const noexcept { return children_.size(); }
  [[nodiscard]] const child& child_at(std::size_t i) const noexcept { return children_[i]; }
  [[nodiscard]] std::span<const child> children() const noexcept { return children_; }
  /// Whether any child is of this part (the world checks that its shape
  /// list has each part a compound uses).
  [[nodiscard]] bool uses(compound_part part) const noexcept {
    return std::any_of(children_.begin(), children_.end(), [&](const child& c) { return c.part == part; });
  }

  /// f(shape, pose) with child i's shape and its pose in the compound's
  /// frame; returns what f returns.
  template <class F>
  decltype(auto) visit(std::size_t i, F&& f) const {
    const child& c = children_[i];
    switch (c.part) {
      case compound_part::sphere: return f(spheres_[c.slot], c.pose);
      case compound_part::box: return f(boxes_[c.slot], c.pose);
      case compound_part::capsule: return f(capsules_[c.slot], c.pose);
      case compound_part::convex_hull: break;
    }
    return f(hulls_[c.slot], c.pose);
  }

  /// Calls f(i) for every child whose box overlaps `box` (in the
  /// compound's frame; touching counts), without allocating.
  template <class F>
  void for_each_overlapping(const aabb<T>& box, F&& f) const {
    const std::span<const std::uint32_t> order = tree_.order();
    tree_.for_each_leaf_overlapping(box, [&](std::uint32_t first, std::uint32_t count) {
      for (std::uint32_t k = first; k < first + count; ++k)
        if (overlaps(children_[order[k]].bounds, box)) f(std::size_t(order[k]));  // a leaf holds up to four
    });
  }
  /// Calls clip = f(i, clip) for every child whose box the segment origin +
  /// t·translation (compound frame), t in [0, clip], may cross, nearer
  /// boxes first; f returns the new clip (its nearest hit so far).
  template <class F>
  void for_each_along_ray(const vec3<T>& origin, const vec3<T>& translation, T max_fraction, F&& f) const {
    const T reach = std::max(max_component(abs(bounds_.lower)), max_component(abs(bounds_.upper)));
    const T slack = T(16) * scalar_traits<T>::epsilon * std::max(reach, max_component(abs(origin)));
    const std::span<const std::uint32_t> order = tree_.order();
    tree_.for_each_leaf_along(origin, translation, max_fraction, slack,
                              [&](std::uint32_t first, std::uint32_t count, T clip) {
                                for (std::uint32_t k = first; k < first + count; ++k)
                                  clip = f(std::size_t(order[k]), clip);
                                return clip;
                              });
  }

  /// m: the smallest half-extent of any child (what the body may cross in a
  /// step before continuous collision sweeps it), and its use as the
  /// narrow phase's weld distance.
  [[nodiscard]] T thinnest_half_extent() const noexcept { return thinnest_; }

  aabb<T> local_aabb() const noexcept { return bounds_; }
  /// The union of the children's own boxes at `pose`: tighter than the
  /// compound's box turned, for a long compound at an angle.
  aabb<T> world_aabb(const transform<T>& pose) const noexcept {
    aabb<T> box = aabb<T>::empty();
    for (std::size_t i = 0; i < children_.size(); ++i)
      box = merge(box, visit(i, [&](const auto& s, const transform<T>& local) { return s.world_aabb(pose * local); }));
    return box;
  }

 private:
  friend class compound_builder<T>;

  void finish() {
    bounds_ = aabb<T>::empty();
    thinnest_ = std::numeric_limits<T>::infinity();
    std::vector<aabb<T>> boxes(children_.size());
    for (std::size_t i = 0; i < children_.size(); ++i) {
      boxes[i] = children_[i].bounds;
      bounds_ = merge(bounds_, boxes[i]);
      thinnest_ = std::min(thinnest_, visit(i, [](const auto& s, const transform<T>&) {
                             return detail::thinnest_half_extent<T>(s);
                           }));
    }
    tree_.build(boxes);
  }

  std::vector<child> children_;
  std::vector<sphere<T>> spheres_;
  std::vector<box<T>> boxes_;
  std::vector<capsule<T>> capsules_;
  std::vector<convex_hull<T>> hulls_;
  detail::triangle_bvh<T> tree_;
  aabb<T> bounds_{};
  T thinnest_ = T(0);
};

/// Collects a compound's children (compound<T>::builder); build() makes
/// the compound.
template <scalar_type T>
class compound_builder {
 public:
  /// Adds `shape` at `pose` in the compound's frame. relative_density
  /// scales the body's material density for this child (a lead keel
  /// under a wooden hull: 11); it must be finite and positive.
  compound_builder& add(const sphere<T>& shape, const transform<T>& pose = transform<T>::identity(),
                        T relative_density = T(1)) {
    return push(result_.spheres_, shape, compound_part::sphere, pose, relative_density);
  }
  compound_builder& add(const box<T>& shape, const transform<T>& pose = transform<T>::identity(),
                        T relative_density = T(1)) {
    return push(result_.boxes_, shape, compound_part::box, pose, relative_density);
  }
  compound_builder& add(const capsule<T>& shape, const transform<T>& pose = transform<T>::identity(),
                        T relative_density = T(1)) {
    return push(result_.capsules_, shape, compound_part::capsule, pose, relative_density);
  }
  compound_builder& add(const convex_hull<T>& shape, const transform<T>& pose = transform<T>::identity(),
                        T relative_density = T(1)) {
    return push(result_.hulls_, shape, compound_part::convex_hull, pose, relative_density);
  }

  /// The compound of the children added so far (at least one), with its
  /// tree built; the builder is left empty. Each child was checked when
  /// added.
  [[nodiscard]] compound<T> build() {
    if (result_.children_.empty())
      detail::report_error(error_code::degenerate_shape, "compound: needs at least one child");
    compound<T> c = std::move(result_);
    result_ = compound<T>{};
    c.finish();
    return c;
  }

 private:
  template <class Shape>
  compound_builder& push(std::vector<Shape>& column, const Shape& shape, compound_part part, const transform<T>& pose,
                T relative_density) {
    shape.validate();
    if (!is_finite(pose.position) || !is_finite(pose.rotation))
      detail::report_error(error_code::non_finite, "compound: a child's pose is not finite");
    if (!is_normalized(pose.rotation))
      detail::report_error(error_code::not_normalized, "compound: a child's rotation is not a unit quaternion");
    if (!std::isfinite(relative_density) || !(relative_density > T(0)))
      detail::report_error(error_code::invalid_parameter,
                           "compound: a child's relative density must be finite and positive");
    if (result_.children_.size() >= compound<T>::max_children)
      detail::report_error(error_code::out_of_range, "compound: more than max_children children");
    column.push_back(shape);
    result_.children_.push_back(
        {pose, shape.world_aabb(pose), relative_density, part, std::uint32_t(column.size() - 1)});
    return *this;
  }

  compound<T> result_;
};

/// The children's mass properties, each at the body's density times its
/// own relative density, placed by its pose and summed: exact for the
/// solid the children make, when they do not overlap (where two overlap,
/// the overlap counts twice, as in Jolt and Bullet).
template <scalar_type T>
mass_properties<T> mass_properties_of(const compound<T>& c, T density) {
  c.validate();
  detail::require_density(density);
  mass_properties<T> sum;
  for (std::size_t i = 0; i < c.child_count(); ++i) {
    const mass_properties<T> part = c.visit(i, [&](const auto& s, const transform<T>& pose) {
      return transformed(mass_properties_of(s, density * c.child_at(i).relative_density), to_mat3(pose.rotation),
                         pose.position);
    });
    sum = i == 0 ? part : combine(sum, part);
  }
  return sum;
}

}  // namespace impulse
