// impulse/shapes/detail/triangle_bvh.hpp — a static bounding-volume
// hierarchy over the triangles of a triangle_mesh.
//
// Built once, top down (Ericson, "Real-Time Collision Detection", §6.2.1):
// a node's triangles are split in two halves at the median of their
// centroids along the longest axis of the centroids' box, until a node
// holds at most leaf_size triangles. The median, not the surface-area
// heuristic, because it bounds the depth by ⌈log2(n / leaf_size)⌉ + 1 (at
// most 31 for 2^32 triangles): queries then walk the tree with a stack of
// fixed size on the call stack and never allocate. SAH trees are ~10–30 %
// cheaper to query on uneven meshes, but their depth is not bounded.
//
// Layout: every node in one array, depth first; an inner node's first child
// follows it, and it stores the index of its second. A leaf stores a range
// of `order()`, the triangle indices permuted so that each leaf's are
// contiguous: the mesh's own triangles keep their indices, which are what
// feature ids and ray hits report.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "../../math/aabb.hpp"
#include "../../math/ray.hpp"
#include "../../math/scalar_traits.hpp"
#include "../../math/vec3.hpp"

namespace impulse::detail {

template <scalar_type T>
struct triangle_bvh_node {
  aabb<T> bounds;        ///< tight around the node's triangles
  std::uint32_t index;   ///< leaf: the first entry of order(); inner: the second child's node index
  std::uint32_t count;   ///< leaf: how many triangles (1 … leaf_size); inner: 0
};

template <scalar_type T>
class triangle_bvh {
 public:
  using node = triangle_bvh_node<T>;
  static constexpr std::uint32_t leaf_size = 4;
  /// Room in a query's stack: the depth bound above, with room to spare.
  static constexpr std::size_t stack_size = 64;

  /// Builds the tree over the triangles whose boxes are `boxes` (one per
  /// triangle, triangle t's at index t). At least one.
  void build(std::span<const aabb<T>> boxes) {
    nodes_.clear();
    order_.resize(boxes.size());
    for (std::uint32_t t = 0; t < boxes.size(); ++t) order_[t] = t;
    // At most 2·⌈n / 1⌉ − 1 nodes; a median split into leaves of up to
    // leaf_size makes about n / 2 of them.
    nodes_.reserve(2 * (boxes.size() / std::size_t(leaf_size) + 1));
    build_node(boxes, 0, std::uint32_t(boxes.size()));
  }

  [[nodiscard]] std::span<const node> nodes() const noexcept { return nodes_; }
  /// The triangle indices in leaf order.
  [[nodiscard]] std::span<const std::uint32_t> order() const noexcept { return order_; }
  /// Bytes the tree holds: its nodes and the leaf order.
  [[nodiscard]] std::size_t memory_bytes() const noexcept {
    return nodes_.capacity() * sizeof(node) + order_.capacity() * sizeof(std::uint32_t);
  }

  /// Calls leaf(first, count) for every leaf whose box overlaps `box`
  /// (closed boxes: touching counts); the leaf's triangles are
  /// order()[first … first + count).
  template <class Leaf>
  void for_each_leaf_overlapping(const aabb<T>& box, Leaf&& leaf) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[stack_size];
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const node& n = nodes_[stack[--top]];
      if (!overlaps(n.bounds, box)) continue;
      if (n.count > 0) {
        leaf(n.index, n.count);
        continue;
      }
      const std::uint32_t first = std::uint32_t(&n - nodes_.data()) + 1;
      stack[top++] = n.index;
      stack[top++] = first;
    }
  }

  /// Walks the leaves that the segment origin + t·translation, t in
  /// [0, max_fraction], may cross, nearer child first. leaf(first, count,
  /// clip) is called with the current clip fraction and returns the new one
  /// (≤ it: the nearest hit so far); boxes entered beyond the clip are
  /// skipped. Each box is grown by `slack` (m) on every side, so that the
  /// slab test's rounding cannot drop a triangle that a triangle test would
  /// hit (a flat mesh has boxes of zero thickness).
  template <class Leaf>
  void for_each_leaf_along(const vec3<T>& origin, const vec3<T>& translation, T max_fraction, T slack,
                           Leaf&& leaf) const {
    if (nodes_.empty()) return;
    T clip = max_fraction;
    struct entry {
      std::uint32_t node;
      T enter;
    };
    entry stack[stack_size];
    std::size_t top = 0;
    T enter = T(0);
    if (!slab(nodes_[0].bounds, origin, translation, clip, slack, enter)) return;
    stack[top++] = {0, enter};
    while (top > 0) {
      const entry e = stack[--top];
      if (e.enter > clip) continue;  // a nearer hit came in since it was pushed
      const node& n = nodes_[e.node];
      if (n.count > 0) {
        clip = leaf(n.index, n.count, clip);
        continue;
      }
      const std::uint32_t first = e.node + 1, second = n.index;
      T enter_first = T(0), enter_second = T(0);
      const bool hit_first = slab(nodes_[first].bounds, origin, translation, clip, slack, enter_first);
      const bool hit_second = slab(nodes_[second].bounds, origin, translation, clip, slack, enter_second);
      // Push the farther first, so that the nearer is walked first.
      if (hit_first && hit_second) {
        if (enter_first <= enter_second) {
          stack[top++] = {second, enter_second};
          stack[top++] = {first, enter_first};
        } else {
          stack[top++] = {first, enter_first};
          stack[top++] = {second, enter_second};
        }
      } else if (hit_first) {
        stack[top++] = {first, enter_first};
      } else if (hit_second) {
        stack[top++] = {second, enter_second};
      }
    }
  }

 private:
  std::uint32_t build_node(std::span<const aabb<T>> boxes, std::uint32_t begin, std::uint32_t end) {
    const std::uint32_t self = std::uint32_t(nodes_.size());
    nodes_.push_back({aabb<T>::empty(), 0, 0});
    aabb<T> bounds = aabb<T>::empty(), centroids = aabb<T>::empty();
    for (std::uint32_t i = begin; i < end; ++i) {
      bounds = merge(bounds, boxes[order_[i]]);
      centroids = merge(centroids, center(boxes[order_[i]]));
    }
    nodes_[self].bounds = bounds;
    if (end - begin <= leaf_size) {
      nodes_[self].index = begin;
      nodes_[self].count = end - begin;
      return self;
    }
    const vec3<T> extent = centroids.upper - centroids.lower;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    const std::uint32_t middle = begin + (end - begin) / 2;
    // Ties broken by index, so that the tree is the same on every platform
    // (nth_element alone leaves equal keys in an unspecified order).
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                     [&](std::uint32_t x, std::uint32_t y) {
                       const T cx = boxes[x].lower[axis] + boxes[x].upper[axis];
                       const T cy = boxes[y].lower[axis] + boxes[y].upper[axis];
                       return cx < cy || (cx == cy && x < y);
                     });
    build_node(boxes, begin, middle);
    const std::uint32_t second = build_node(boxes, middle, end);
    nodes_[self].index = second;
    return self;
  }

  /// The slab test (Kay and Kajiya 1986) of the segment against `box`
  /// grown by `slack`: the fraction where it enters, if within [0, clip].
  static bool slab(const aabb<T>& box, const vec3<T>& origin, const vec3<T>& translation, T clip, T slack,
                   T& enter) noexcept {
    const vec3<T> grow = vec3<T>::splat(slack);
    const std::optional<T> t = ray_enters(ray<T>{origin, translation}, clip, aabb<T>{box.lower - grow, box.upper + grow});
    if (t) enter = *t;
    return t.has_value();
  }

  std::vector<node> nodes_;
  std::vector<std::uint32_t> order_;
};

}  // namespace impulse::detail
