// expect: missing_pair_test<impulse::sphere<float>, ?lump<float>, ?float ?>
// A shape listed beside a sphere but with no collide against one: the
// build fails and the error names the pair.
#include "impulse/narrowphase/dispatch.hpp"

template <class T>
struct lump {
  static constexpr impulse::policy_kind kind = impulse::policy_kind::shape;
  T radius;
};
template <class T>
impulse::contact_manifold<T> collide(const lump<T>&, const impulse::transform<T>&, const lump<T>&,
                                     const impulse::transform<T>&, T) {
  return {};
}

using dispatch = impulse::narrowphase::dispatcher<impulse::shape_list<impulse::sphere, lump>, float>;

int main() {
  const lump<float> a{0.5f};
  impulse::contact_manifold<float> out[1];
  return int(dispatch::collide(dispatch::ref(a), {}, dispatch::ref(a), {}, 0.0f, out));
}
