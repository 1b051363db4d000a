// The worlds without collision of tests/dynamics/motion_test.hpp, one per
// scalar and integrator, compiled once for the unit-test executable
// (IMPULSE_TEST_WORLDS_EXTERN: every other file only parses them).
#include "../dynamics/motion_test.hpp"

IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<float, impulse::integrators::euler>);
IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<float, impulse::integrators::symplectic_euler>);
IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<float, impulse::integrators::midpoint>);
IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<float, impulse::integrators::rk4>);
IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<double, impulse::integrators::euler>);
IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<double, impulse::integrators::symplectic_euler>);
IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<double, impulse::integrators::midpoint>);
IMPULSE_INSTANTIATE_WORLD(impulse::test::motion_config<double, impulse::integrators::rk4>);
