// The scene reader (impulse/io/scene.hpp) of float and double, compiled once
// for the examples and the tests that read scene files: they are built with
// IMPULSE_EXTERN_SCENE_READER=1 and only parse it.
#include "impulse/io/scene.hpp"

IMPULSE_INSTANTIATE_SCENE_READER(float);
IMPULSE_INSTANTIATE_SCENE_READER(double);
