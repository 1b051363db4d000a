// A program that uses impulse the way a downstream project would; built by
// tests/consumer/run.sh through find_package, add_subdirectory, a Meson
// subproject, pkg-config and the single header alone.
#include <cstdio>

#include "impulse/impulse.hpp"

struct consumer_config : impulse::default_config {
  using scalar = double;
};
static_assert(impulse::check_config<consumer_config>());

int main() {
  using T = consumer_config::scalar;
  const impulse::vec3<T> axis{0, 0, 1};
  const impulse::quat<T> quarter = impulse::quat<T>::from_axis_angle(axis, 1.5707963267948966);
  const impulse::vec3<T> turned = impulse::rotate(quarter, impulse::vec3<T>::unit_x());
  std::printf("impulse %s: x turned a quarter about z is (%.3f, %.3f, %.3f)\n",
              IMPULSE_VERSION_STRING, turned.x, turned.y, turned.z);
  const bool ok = impulse::distance(turned, impulse::vec3<T>::unit_y()) < 1e-12;
  return ok ? 0 : 1;
}
