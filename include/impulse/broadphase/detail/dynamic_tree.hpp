// impulse/broadphase/detail/dynamic_tree.hpp — a dynamic AABB tree: a binary
// bounding volume hierarchy over boxes that come, go and move, kept good
// by local repairs instead of rebuilds.
//
// The structure of Box2D's b2DynamicTree and Bullet's btDbvt (Catto, "Dynamic
// Bounding Volume Hierarchies", GDC 2019; Ericson, Real-Time Collision
// Detection, §6.2): nodes live in one array and name each other by index,
// freed nodes are chained into a free list through their parent field, so
// a leaf's index is stable for its whole life and the tree allocates only
// while its array grows to the high-water mark.
//
// Quality is measured by the surface-area heuristic (Goldsmith and Salmon
// 1987; MacDonald and Booth 1990): a small random box or ray inside the
// root enters a node with a probability proportional to the node's surface
// area, so the expected cost of a query is the internal nodes' summed area
// over the root's. Insertion looks for the sibling that adds the least
// area: a greedy descent that carries the ancestors' growth down as an
// inherited cost and stops when a lower bound says no deeper place can win
// (Box2D v3's b2FindBestSibling works the same way). The walk back up
// refits each ancestor and applies there the tree rotation that most
// reduces area, if any (Kopta et al., "Fast, Effective BVH Updates for
// Animated Scenes", I3D 2012; Box2D v3's b2RotateNodes).
//
// Rotations by area rather than AVL balancing by height (Box2D v2.4):
// balancing keeps the tree shallow but pairs boxes regardless of how far
// apart they are, and area is what queries pay for. Rotations keep the
// height logarithmic in practice too, including for the classic degenerate
// case of boxes inserted in sorted order along a line: a long spine has
// large internal boxes, which the rotations remove (4096 boxes in a row
// give height 14, log2 n = 12; the tests hold it to 2·log2 n + 2). The
// rotations include exchanging grandchildren across (a child of b with a
// child of c), not only a child with a grandchild: without them a tree
// under steady motion settles about 20 % worse by the heuristic and takes
// 30 % more node visits to collide with itself (measured at 10^5 boxes).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "../../math/aabb.hpp"

namespace impulse::broadphase::detail {

inline constexpr std::int32_t null_node = -1;

template <scalar_type T>
struct tree_node {
  aabb<T> box;                      ///< a leaf's box as given; an internal node's is its children's union
  std::int32_t parent = null_node;  ///< next free node while on the free list
  std::int32_t child1 = null_node;  ///< null_node for a leaf
  std::int32_t child2 = null_node;
  std::int32_t height = 0;          ///< 0 for a leaf, -1 for a free node
  std::uint32_t payload = 0;        ///< a leaf's owner data (the broad phase's proxy slot)
  /// A stamp the owner may write to flag nodes (the broad phase marks the
  /// ancestors of changed leaves with the current update's number); the
  /// tree never reads it.
  std::uint32_t mark = 0;

  [[nodiscard]] bool is_leaf() const noexcept { return child1 == null_node; }
};

/// A stack of node indices for a traversal: a fixed buffer that covers any
/// tree of practical height, spilling to the heap only beyond it, so that a
/// const query needs neither shared scratch space nor an allocation.
class node_stack {
 public:
  void push(std::int32_t node) {
    if (size_ < inline_capacity)
      inline_[size_] = node;
    else
      spill_.push_back(node);
    ++size_;
  }
  std::int32_t pop() noexcept {
    --size_;
    if (size_ < inline_capacity) return inline_[size_];
    const std::int32_t node = spill_.back();
    spill_.pop_back();
    return node;
  }
  [[nodiscard]] bool empty() const noexcept { return size_ == 0; }

 private:
  // A depth-first traversal holds at most height + 1 entries.
  static constexpr std::size_t inline_capacity = 128;
  std::int32_t inline_[inline_capacity];
  std::size_t size_ = 0;
  std::vector<std::int32_t> spill_;
};

template <scalar_type T>
class dynamic_tree {
 public:
  /// Adds a leaf with this box; returns its node index, stable until destroy_leaf.
  std::int32_t create_leaf(const aabb<T>& box, std::uint32_t payload) {
    const std::int32_t leaf = allocate();
    nodes_[leaf].box = box;
    nodes_[leaf].height = 0;
    nodes_[leaf].payload = payload;
    insert_leaf(leaf, root_);
    return leaf;
  }

  void destroy_leaf(std::int32_t leaf) {
    remove_leaf(leaf);
    release(leaf);
  }

  /// Gives the leaf a new box and re-inserts it where the new box fits
  /// best. The search starts from the lowest ancestor of the leaf's old
  /// place that contains the new box rather than from the root: every
  /// ancestor above that one contains it too, so would grow by nothing,
  /// and a box that moved a little finds its new place a few levels up
  /// instead of a whole height's descent away (this halved the cost of a
  /// re-insertion at 10^4 boxes, for the same tree quality).
  void move_leaf(std::int32_t leaf, const aabb<T>& box) {
    if (leaf == root_) {
      nodes_[leaf].box = box;
      return;
    }
    const std::int32_t parent = nodes_[leaf].parent;
    std::int32_t start = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    remove_leaf(leaf);
    while (start != root_ && !contains(nodes_[start].box, box)) start = nodes_[start].parent;
    nodes_[leaf].box = box;
    insert_leaf(leaf, start);
  }

  [[nodiscard]] const aabb<T>& box(std::int32_t node) const noexcept { return nodes_[node].box; }
  [[nodiscard]] std::int32_t root() const noexcept { return root_; }
  [[nodiscard]] const std::vector<tree_node<T>>& nodes() const noexcept { return nodes_; }
  /// Writable for the owner's marks; the structure is the tree's to change.
  [[nodiscard]] std::vector<tree_node<T>>& nodes() noexcept { return nodes_; }

  /// Nodes in use: 2n − 1 for n leaves (0 when empty).
  [[nodiscard]] std::size_t node_count() const noexcept { return used_; }
  /// Edges on the longest path from the root to a leaf (0 for one leaf or none).
  [[nodiscard]] int height() const noexcept { return root_ == null_node ? 0 : nodes_[root_].height; }
  /// The surface-area-heuristic cost: the internal nodes' summed surface
  /// areas over the root's, the expected number of internal nodes a small
  /// random box inside the root enters. 0 when there is no internal node
  /// (or the root has no area).
  [[nodiscard]] T sah_cost() const noexcept {
    if (root_ == null_node) return T(0);
    const T root_area = surface_area(nodes_[root_].box);
    if (!(root_area > T(0))) return T(0);
    T total = T(0);
    for (const tree_node<T>& n : nodes_)
      if (n.height > 0) total += surface_area(n.box);
    return total / root_area;
  }

  /// Calls visit(leaf) for every leaf whose box overlaps `box`.
  template <class Visit>
  void query(const aabb<T>& box, Visit&& visit) const {
    if (root_ == null_node) return;
    node_stack stack;
    stack.push(root_);
    while (!stack.empty()) {
      const std::int32_t index = stack.pop();
      const tree_node<T>& n = nodes_[index];
      if (!overlaps(n.box, box)) continue;
      if (n.is_leaf()) {
        visit(index);
      } else {
        stack.push(n.child1);
        stack.push(n.child2);
      }
    }
  }

 private:
  static T merged_area(const aabb<T>& a, const aabb<T>& b) noexcept { return surface_area(merge(a, b)); }

  std::int32_t allocate() {
    std::int32_t node;
    if (free_ == null_node) {
      node = static_cast<std::int32_t>(nodes_.size());
      nodes_.emplace_back();
    } else {
      node = free_;
      free_ = nodes_[node].parent;
      nodes_[node] = tree_node<T>{};
    }
    ++used_;
    return node;
  }

  void release(std::int32_t node) noexcept {
    nodes_[node].parent = free_;
    nodes_[node].child1 = nodes_[node].child2 = null_node;
    nodes_[node].height = -1;
    free_ = node;
    --used_;
  }

  /// The node under `start` whose sibling the new box should become. At
  /// each internal node on the way down: making the box the sibling of
  /// either child costs the new parent's area plus the growth of every
  /// ancestor; any place deeper inside a child costs at least the
  /// ancestors' growth, the child's own growth and a new parent no smaller
  /// than the box. The descent follows the child with the lower bound and
  /// stops when that bound cannot beat the best place seen.
  std::int32_t best_sibling(const aabb<T>& box, std::int32_t start) const noexcept {
    const T box_area = surface_area(box);
    std::int32_t best = start;
    T best_cost = merged_area(nodes_[start].box, box);
    T inherited = T(0);  // growth of `index` and its ancestors below start
    std::int32_t index = start;
    while (!nodes_[index].is_leaf()) {
      const tree_node<T>& n = nodes_[index];
      inherited += merged_area(n.box, box) - surface_area(n.box);
      const std::int32_t children[2] = {n.child1, n.child2};
      T lower[2];
      for (int k = 0; k < 2; ++k) {
        const tree_node<T>& c = nodes_[children[k]];
        const T combined = merged_area(c.box, box);
        const T direct = combined + inherited;
        if (direct < best_cost) best = children[k], best_cost = direct;
        lower[k] = c.is_leaf() ? std::numeric_limits<T>::infinity()
                               : inherited + (combined - surface_area(c.box)) + box_area;
      }
      const int k = lower[1] < lower[0] ? 1 : 0;
      if (!(lower[k] < best_cost)) break;
      index = children[k];
    }
    return best;
  }

  /// Inserts the leaf as the sibling of the best node under `start`,
  /// which is the root or contains the leaf's box.
  void insert_leaf(std::int32_t leaf, std::int32_t start) {
    if (root_ == null_node) {
      root_ = leaf;
      nodes_[leaf].parent = null_node;
      return;
    }
    const std::int32_t sibling = best_sibling(nodes_[leaf].box, start);
    const std::int32_t parent = allocate();  // may grow nodes_: no references held across it
    const std::int32_t grandparent = nodes_[sibling].parent;
    tree_node<T>& p = nodes_[parent];
    p.parent = grandparent;
    p.child1 = sibling;
    p.child2 = leaf;
    p.box = merge(nodes_[sibling].box, nodes_[leaf].box);
    p.height = nodes_[sibling].height + 1;
    nodes_[sibling].parent = parent;
    nodes_[leaf].parent = parent;
    if (grandparent == null_node) {
      root_ = parent;
    } else {
      tree_node<T>& g = nodes_[grandparent];
      (g.child1 == sibling ? g.child1 : g.child2) = parent;
    }
    rotate(parent);
    refit_from(grandparent, true);
  }

  /// Takes the leaf out; its sibling takes their parent's place. Removal
  /// only shrinks boxes, so the walk up refits without rotating: rotating
  /// there as well nearly doubled the rotations tried for no measurable
  /// gain in quality.
  void remove_leaf(std::int32_t leaf) {
    if (leaf == root_) {
      root_ = null_node;
      return;
    }
    const std::int32_t parent = nodes_[leaf].parent;
    const std::int32_t grandparent = nodes_[parent].parent;
    const std::int32_t sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    nodes_[sibling].parent = grandparent;
    if (grandparent == null_node) {
      root_ = sibling;
    } else {
      tree_node<T>& g = nodes_[grandparent];
      (g.child1 == parent ? g.child1 : g.child2) = sibling;
    }
    release(parent);
    refit_from(grandparent, false);
  }

  /// Walks from `index` towards the root: each ancestor's box and height
  /// from its children, then (when asked) the best rotation there. Stops
  /// at the first ancestor whose box and height come out unchanged, as
  /// Bullet's removeleaf does: nothing above it can change either, so most
  /// walks end a few levels up instead of at the root.
  void refit_from(std::int32_t index, bool rotating) noexcept {
    while (index != null_node) {
      const aabb<T> old_box = nodes_[index].box;
      const std::int32_t old_height = nodes_[index].height;
      refit(index);
      if (rotating) rotate(index);
      const tree_node<T>& n = nodes_[index];
      if (n.box == old_box && n.height == old_height) return;
      index = n.parent;
    }
  }

  void refit(std::int32_t index) noexcept {
    tree_node<T>& n = nodes_[index];
    n.box = merge(nodes_[n.child1].box, nodes_[n.child2].box);
    n.height = 1 + std::max(nodes_[n.child1].height, nodes_[n.child2].height);
  }

  /// Exchanges two subtrees, neither inside the other.
  void swap_subtrees(std::int32_t x, std::int32_t y) noexcept {
    const std::int32_t px = nodes_[x].parent, py = nodes_[y].parent;
    (nodes_[px].child1 == x ? nodes_[px].child1 : nodes_[px].child2) = y;
    (nodes_[py].child1 == y ? nodes_[py].child1 : nodes_[py].child2) = x;
    nodes_[x].parent = py;
    nodes_[y].parent = px;
  }

  /// At node a with children b and c: exchanges a child with a grandchild
  /// on the other side (b with one of c's children, or c with one of b's)
  /// or two grandchildren across (one of b's with one of c's), whichever
  /// shrinks the summed area of a's children the most, if any does. a's
  /// own box holds the same leaves either way, so nothing above a changes.
  void rotate(std::int32_t a) noexcept {
    const tree_node<T>& na = nodes_[a];
    if (na.height < 2) return;
    const std::int32_t b = na.child1, c = na.child2;
    const tree_node<T>& nb = nodes_[b];
    const tree_node<T>& nc = nodes_[c];

    std::int32_t best_x = null_node, best_y = null_node;
    T best_delta = T(0);  // only a strict reduction is worth a rotation
    const auto consider = [&](std::int32_t x, std::int32_t y, T delta) {
      if (delta < best_delta) best_x = x, best_y = y, best_delta = delta;
    };
    const T area_b = surface_area(nb.box), area_c = surface_area(nc.box);
    if (!nc.is_leaf()) {
      // b with one of c's children: c becomes b and the other child.
      consider(b, nc.child1, merged_area(nb.box, nodes_[nc.child2].box) - area_c);
      consider(b, nc.child2, merged_area(nb.box, nodes_[nc.child1].box) - area_c);
    }
    if (!nb.is_leaf()) {
      // c with one of b's children: b becomes c and the other child.
      consider(c, nb.child1, merged_area(nc.box, nodes_[nb.child2].box) - area_b);
      consider(c, nb.child2, merged_area(nc.box, nodes_[nb.child1].box) - area_b);
    }
    if (!nb.is_leaf() && !nc.is_leaf()) {
      // One of b's children with one of c's.
      const std::int32_t bs[2] = {nb.child1, nb.child2}, cs[2] = {nc.child1, nc.child2};
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          const aabb<T>& stays_in_b = nodes_[bs[1 - i]].box;
          const aabb<T>& stays_in_c = nodes_[cs[1 - j]].box;
          consider(bs[i], cs[j],
                   merged_area(stays_in_b, nodes_[cs[j]].box) + merged_area(stays_in_c, nodes_[bs[i]].box) -
                       area_b - area_c);
        }
    }
    if (best_x == null_node) return;
    swap_subtrees(best_x, best_y);
    const tree_node<T>& after = nodes_[a];
    if (!nodes_[after.child1].is_leaf()) refit(after.child1);
    if (!nodes_[after.child2].is_leaf()) refit(after.child2);
    refit(a);
  }

  std::vector<tree_node<T>> nodes_;
  std::int32_t root_ = null_node;
  std::int32_t free_ = null_node;
  std::size_t used_ = 0;
};

}  // namespace impulse::broadphase::detail
