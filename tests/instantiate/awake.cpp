// The float worlds of tests/world/scenes.hpp, compiled once for the
// unit-test executable (IMPULSE_TEST_WORLDS_EXTERN: every other file only
// parses them).
#include "../world/scenes.hpp"

IMPULSE_INSTANTIATE_WORLD(impulse::test::awake_config);
IMPULSE_INSTANTIATE_WORLD(impulse::test::sleeping_config);
IMPULSE_INSTANTIATE_WORLD(impulse::test::soft_config);
IMPULSE_INSTANTIATE_WORLD(impulse::test::ccd_config);
