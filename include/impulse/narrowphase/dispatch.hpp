// impulse/narrowphase/dispatch.hpp — the pair tests a world is compiled
// for, chosen from its config's shape_list.
//
// `dispatcher<shape_list<sphere, box>, float>` holds a table of one entry
// per ordered pair of listed shapes, each entry the `collide` written for
// that pair (sphere–box, box–sphere, …), called through the shapes'
// indices in the list. Only the listed pairs are instantiated: a world of
// spheres and boxes compiles none of the hull, capsule or GJK code. Two
// shapes that are only ever static (planes, triangle meshes) never meet,
// and their entry returns an empty manifold.
//
// A listed pair with no `collide` is a compile error whose instantiation
// context names the pair: `missing_pair_test<A, B, T>`. A user's own shape
// joins by providing `collide(const mine<T>&, const transform<T>&, const
// other<T>&, const transform<T>&, T margin)` for each shape it is listed
// with, in its own namespace (found by argument-dependent lookup) or in
// impulse::narrowphase.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "../core/assert.hpp"
#include "../core/policy.hpp"
#include "../math/transform.hpp"
#include "../shapes/plane.hpp"
#include "../shapes/triangle_mesh.hpp"
#include "analytic.hpp"
#include "box_box.hpp"
#include "capsule_polyhedron.hpp"
#include "hull.hpp"
#include "hull_hull.hpp"
#include "manifold.hpp"

namespace impulse::narrowphase {

/// Whether `collide(a, pose_a, b, pose_b, margin)` is written for shapes A
/// then B, in scalar T.
template <class A, class B, class T>
concept has_pair_test = requires(const A& a, const B& b, const transform<T>& pose, T margin) {
  { collide(a, pose, b, pose, margin) } -> std::same_as<contact_manifold<T>>;
};

/// Shapes that only static bodies have (planes, triangle meshes): two of
/// them never need a pair test.
template <class S>
inline constexpr bool static_only = false;
template <scalar_type T>
inline constexpr bool static_only<plane<T>> = true;
template <scalar_type T>
inline constexpr bool static_only<triangle_mesh<T>> = true;

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
contact_manifold<T> call_collide(const void* a, const transform<T>& pose_a, const void* b, const transform<T>& pose_b,
                                 T margin) {
  if constexpr (static_only<A> && static_only<B>) {
    return {};
  } else if constexpr (missing_pair_test<A, B, T>::value) {
    return collide(*static_cast<const A*>(a), pose_a, *static_cast<const B*>(b), pose_b, margin);
  } else {
    return {};  // not reached: missing_pair_test has failed the build
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

  /// The manifold of a and b, by the test written for their pair.
  static contact_manifold<T> collide(const shape_ref& a, const transform<T>& pose_a, const shape_ref& b,
                                     const transform<T>& pose_b, T margin = T(0)) {
    IMPULSE_ASSERT(a.index < shape_count && b.index < shape_count);
    return table[a.index * shape_count + b.index](a.shape, pose_a, b.shape, pose_b, margin);
  }

 private:
  using pair_test = contact_manifold<T> (*)(const void*, const transform<T>&, const void*, const transform<T>&, T);

  template <std::size_t... I>
  static constexpr std::array<pair_test, shape_count * shape_count> make_table(std::index_sequence<I...>) noexcept {
    return {&detail::call_collide<shape_at<I / shape_count>, shape_at<I % shape_count>, T>...};
  }
  static constexpr std::array<pair_test, shape_count * shape_count> table =
      make_table(std::make_index_sequence<shape_count * shape_count>{});
};

}  // namespace impulse::narrowphase
