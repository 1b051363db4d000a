// impulse/narrowphase/dispatch.hpp — the pair tests a world is compiled
// for, chosen from its config's shape_list.
//
// `dispatcher<shape_list<sphere, box>, float>` holds a table of one entry
// per ordered pair of listed shapes, each entry the `collide` written for
// that pair (sphere–box, box–sphere, …), called through the shapes'
// indices in the list. Every entry writes its manifolds into a span and
// returns how many: one for a pair of convex shapes, one per distinct
// normal for a mesh (mesh.hpp). Only the listed pairs are instantiated: a world of
// spheres and boxes compiles none of the hull, capsule or GJK code. Two
// shapes that are only ever static (planes, triangle meshes) never meet,
// and their entry returns an empty manifold.
//
// A listed pair with no `collide` is a compile error whose instantiation
// context names the pair: `missing_pair_test<A, B, T>`. A user's own shape
// joins by providing `collide(const mine<T>&, const transform<T>&, const
// other<T>&, const transform<T>&, T margin)` for each shape it is listed
// with, in its own namespace (found by argument-dependent lookup) or in
// impulse::narrowphase; or the form with `std::span<contact_manifold<T>>
// out` last, returning how many it wrote.
//
// A compound has no entry of its own: collide() takes its children one by
// one through the table (compound.hpp), so a compound costs no pair test
// beyond those of its children's shapes, which the list must hold.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>
#include <utility>

#include "../core/detail/assert.hpp"
#include "../core/policy.hpp"
#include "../math/transform.hpp"
#include "../shapes/plane.hpp"
#include "../shapes/heightfield.hpp"
#include "../shapes/triangle_mesh.hpp"
#include "analytic.hpp"
#include "box_box.hpp"
#include "capsule_polyhedron.hpp"
#include "compound.hpp"
#include "hull.hpp"
#include "hull_hull.hpp"
#include "manifold.hpp"
#include "mesh.hpp"

namespace impulse::narrowphase {

/// Whether `collide(a, pose_a, b, pose_b, margin)` is written for shapes A
/// then B, in scalar T, giving one manifold…
template <class A, class B, class T>
concept has_manifold_test = requires(const A& a, const B& b, const transform<T>& pose, T margin) {
  { collide(a, pose, b, pose, margin) } -> std::same_as<contact_manifold<T>>;
};
/// …or `collide(a, pose_a, b, pose_b, margin, out)`, writing several into
/// `out` and returning how many (a mesh: one per distinct normal).
template <class A, class B, class T>
concept has_manifolds_test =
    requires(const A& a, const B& b, const transform<T>& pose, T margin, std::span<contact_manifold<T>> out) {
      { collide(a, pose, b, pose, margin, out) } -> std::same_as<std::size_t>;
    };
template <class A, class B, class T>
concept has_pair_test = has_manifold_test<A, B, T> || has_manifolds_test<A, B, T>;

/// Shapes that only static bodies have (planes, triangle meshes): two of
/// them never need a pair test.
template <class S>
inline constexpr bool static_only = false;
template <scalar_type T>
inline constexpr bool static_only<plane<T>> = true;
template <scalar_type T>
inline constexpr bool static_only<triangle_mesh<T>> = true;
template <scalar_type T>
inline constexpr bool static_only<heightfield<T>> = true;

namespace detail {

/// Instantiated for a listed pair without a test, so that the compiler's
/// error names the pair in this template's arguments.
template <class A, class B, class T>
struct missing_pair_test {
  static_assert(has_pair_test<A, B, T>,
                "impulse: the config's shape_list lists a pair of shapes that has no narrow-phase test "
                "(the pair is named in missing_pair_test<A, B, T>): write collide(const A&, const "
                "transform<T>&, const B&, const transform<T>&, T margin), or take one of them out of the list");
  static constexpr bool value = has_pair_test<A, B, T>;
};

/// The I-th of the types Ts.
template <std::size_t I, class First, class... Rest>
struct type_at {
  using type = typename type_at<I - 1, Rest...>::type;
};
template <class First, class... Rest>
struct type_at<0, First, Rest...> {
  using type = First;
};

/// The call, where unqualified lookup sees every collide above and
/// argument-dependent lookup adds the user's.
template <class A, class B, class T>
std::size_t call_collide(const void* a, const transform<T>& pose_a, const void* b, const transform<T>& pose_b, T margin,
                         std::span<contact_manifold<T>> out) {
  const A& shape_a = *static_cast<const A*>(a);
  const B& shape_b = *static_cast<const B*>(b);
  if constexpr ((static_only<A> && static_only<B>) || std::is_same_v<A, compound<T>> ||
                std::is_same_v<B, compound<T>>) {
    return 0;  // never met, or (a compound) taken child by child before the table
  } else if constexpr (!missing_pair_test<A, B, T>::value) {
    return 0;  // not reached: missing_pair_test has failed the build
  } else if constexpr (has_manifolds_test<A, B, T>) {
    return collide(shape_a, pose_a, shape_b, pose_b, margin, out);
  } else {
    if (out.empty()) return 0;
    out[0] = collide(shape_a, pose_a, shape_b, pose_b, margin);
    return out[0].empty() ? 0 : 1;
  }
}

}  // namespace detail

template <class List, scalar_type T>
class dispatcher;

template <template <class> class... Shapes, scalar_type T>
class dispatcher<shape_list<Shapes...>, T> {
  template <std::size_t I>
  using shape_at = typename detail::type_at<I, Shapes<T>...>::type;

  template <class S>
  static constexpr std::uint32_t find() noexcept {
    constexpr bool same[] = {std::is_same_v<S, Shapes<T>>..., false};
    for (std::uint32_t i = 0; i < sizeof...(Shapes); ++i)
      if (same[i]) return i;
    return std::uint32_t(sizeof...(Shapes));
  }

 public:
  static constexpr std::size_t shape_count = sizeof...(Shapes);

  /// S's place in the list.
  template <class S>
  static constexpr std::uint32_t index_of = find<S>();

  /// A listed shape: its address and its place in the list (what a world
  /// keeps for each body's shape).
  struct shape_ref {
    const void* shape;
    std::uint32_t index;
  };
  template <class S>
  static constexpr shape_ref ref(const S& shape) noexcept {
    static_assert(index_of<S> < shape_count, "impulse: this shape is not in the config's shape_list");
    return {&shape, index_of<S>};
  }

  /// The manifolds of a and b, by the test written for their pair: at most
  /// out.size() (one, but for a mesh one per distinct normal), written to
  /// out; returns how many.
  static std::size_t collide(const shape_ref& a, const transform<T>& pose_a, const shape_ref& b,
                             const transform<T>& pose_b, T margin, std::span<contact_manifold<T>> out) {
    IMPULSE_ASSERT(a.index < shape_count && b.index < shape_count);
    if constexpr (compound_index < shape_count)
      if (a.index == compound_index || b.index == compound_index)
        return collide_compound_pair(a, pose_a, b, pose_b, margin, out);
    return table[a.index * shape_count + b.index](a.shape, pose_a, b.shape, pose_b, margin, out);
  }

  /// Whether the list holds the shape of every child of `c` (a world
  /// refuses a compound it could not test).
  static bool holds_children_of(const compound<T>& c) noexcept {
    for (std::size_t k = 0; k < part_index.size(); ++k)
      if (part_index[k] == shape_count && c.uses(compound_part(k))) return false;
    return true;
  }

 private:
  static constexpr std::uint32_t compound_index = index_of<compound<T>>;
  /// Each compound_part's place in the list (shape_count: not listed).
  static constexpr std::array<std::uint32_t, 4> part_index = {index_of<sphere<T>>, index_of<box<T>>,
                                                              index_of<capsule<T>>, index_of<convex_hull<T>>};

  /// Child i of c as a listed shape.
  static shape_ref child_ref(const compound<T>& c, std::size_t i) noexcept {
    const void* shape = c.visit(i, [](const auto& s, const transform<T>&) { return static_cast<const void*>(&s); });
    return {shape, part_index[std::size_t(c.child_at(i).part)]};
  }

  /// A pair with a compound, child by child; a child against a compound
  /// (the other side of two compounds) comes back here for that one's
  /// children.
  static std::size_t collide_compound_pair(const shape_ref& a, const transform<T>& pose_a, const shape_ref& b,
                                           const transform<T>& pose_b, T margin, std::span<contact_manifold<T>> out) {
    if (a.index == compound_index) {
      const compound<T>& c = *static_cast<const compound<T>*>(a.shape);
      return collide_compound(c, pose_a, bounds[b.index](b.shape, pose_b), margin, false, out,
                              [&](std::size_t i, const transform<T>& pose, std::span<contact_manifold<T>> part) {
                                return collide(child_ref(c, i), pose, b, pose_b, margin, part);
                              });
    }
    const compound<T>& c = *static_cast<const compound<T>*>(b.shape);
    return collide_compound(c, pose_b, bounds[a.index](a.shape, pose_a), margin, true, out,
                            [&](std::size_t i, const transform<T>& pose, std::span<contact_manifold<T>> part) {
                              return collide(a, pose_a, child_ref(c, i), pose, margin, part);
                            });
  }

  /// Each listed shape's world box, for a compound to find its children
  /// near it.
  using bounds_of = aabb<T> (*)(const void*, const transform<T>&);
  template <class S>
  static aabb<T> call_bounds(const void* s, const transform<T>& pose) noexcept {
    return static_cast<const S*>(s)->world_aabb(pose);
  }
  static constexpr std::array<bounds_of, shape_count> bounds = {&call_bounds<Shapes<T>>...};

  using pair_test = std::size_t (*)(const void*, const transform<T>&, const void*, const transform<T>&, T,
                                    std::span<contact_manifold<T>>);

  template <std::size_t... I>
  static constexpr std::array<pair_test, shape_count * shape_count> make_table(std::index_sequence<I...>) noexcept {
    return {&detail::call_collide<shape_at<I / shape_count>, shape_at<I % shape_count>, T>...};
  }
  static constexpr std::array<pair_test, shape_count * shape_count> table =
      make_table(std::make_index_sequence<shape_count * shape_count>{});
};

}  // namespace impulse::narrowphase
