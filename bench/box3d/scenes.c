// bench/box3d/scenes.c — the standard scenes of docs/standard_scenes.md, and
// its tower, on Box3D (Box2D v3's 3D successor), to time and measure them
// beside impulse in the same run. Box3D is not a Debian package, so this
// file is not built by CMake: fetch Box3D (github.com/erincatto/box3d; the
// figures in docs/world.md are of commit 30c67b5), build its library, and
// compile this file against it:
//
//   cmake -S box3d -B box3d/build -G Ninja -DCMAKE_BUILD_TYPE=Release -DBOX3D_SAMPLES=OFF
//         -DBOX3D_UNIT_TESTS=OFF -DBOX3D_VALIDATE=OFF             (one line)
//   ninja -C box3d/build
//   cc -O2 -I box3d/include bench/box3d/scenes.c box3d/build/src/libbox3d.a -lm -lpthread -o box3d_scenes
//
//   box3d_scenes pile_nosleep | pyramid_nosleep | spheres_nosleep | large_pyramid
//       prints "box3d SCENE MS ms/step": the median of the last 300 steps
//       (the last half of shorter runs), as bench/scenes
//   box3d_scenes tower N [norecycle]
//       N unit boxes stacked as docs/stacks.md's tower, 60 s: prints the
//       top's drift and height lost every 10 s, or when it falls;
//       `norecycle` turns Box3D's contact recycling off
//   box3d_scenes stack R [pair]
//       unit boxes of 1, R, 1, R kg stacked (two, 1 under R, with `pair`),
//       10 s: prints the top's greatest sink and slide
//
// World defaults (4 substeps, 30 Hz contacts, one worker), sleeping off,
// gravity (0, -9.81, 0), dt 1/60 s; mass 1 per body unless a scene says.
#include "box3d/box3d.h"
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
static double now_ms(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e3 + t.tv_nsec * 1e-6;
}

static int by_value(const void* a, const void* b) {
  const double x = *(const double*)a, y = *(const double*)b;
  return x < y ? -1 : x > y;
}

static b3WorldId world;

static b3WorldId make_world(void) {
  b3WorldDef def = b3DefaultWorldDef();
  def.gravity = (b3Vec3){0, -9.81f, 0};
  def.enableSleep = false;
  return b3CreateWorld(&def);
}

static b3BodyId new_body(b3BodyType type, b3Vec3 at) {
  b3BodyDef def = b3DefaultBodyDef();
  def.type = type;
  def.position = (b3Pos){at.x, at.y, at.z};
  return b3CreateBody(world, &def);
}

/// The scenes' surface: friction 0.6, restitution 0.
static b3ShapeDef surface(float density) {
  b3ShapeDef shape = b3DefaultShapeDef();
  shape.density = density;
  shape.baseMaterial.friction = 0.6f;
  return shape;
}

static b3BodyId add_box(b3BodyType type, b3Vec3 at, b3Vec3 half, float density) {
  const b3BodyId id = new_body(type, at);
  const b3ShapeDef shape = surface(density);
  const b3BoxHull hull = b3MakeBoxHull(half.x, half.y, half.z);
  b3CreateHullShape(id, &shape, &hull.base);
  return id;
}

static void add_sphere(b3Vec3 at, float radius, float density) {
  const b3ShapeDef shape = surface(density);
  const b3Sphere sphere = {{0, 0, 0}, radius};
  b3CreateSphereShape(new_body(b3_dynamicBody, at), &shape, &sphere);
}

/// The tower of docs/stacks.md: unit boxes of density 1000.
static int tower(int n, bool no_recycling) {
  world = make_world();
  add_box(b3_staticBody, (b3Vec3){0, -1, 0}, (b3Vec3){100, 1, 100}, 1);
  b3BodyId top = b3_nullBodyId;
  for (int k = 0; k < n; ++k) {
    top = add_box(b3_dynamicBody, (b3Vec3){0, 0.5f + k, 0}, (b3Vec3){0.5f, 0.5f, 0.5f}, 1000);
    b3Body_EnableContactRecycling(top, !no_recycling);
  }
  const b3Pos start = b3Body_GetPosition(top);
  for (int frame = 1; frame <= 3600; ++frame) {
    b3World_Step(world, 1.0f / 60, 4);
    const b3Pos p = b3Body_GetPosition(top);
    const float lost = start.y - p.y, drift = hypotf(p.x - start.x, p.z - start.z);
    if (frame % 600 == 0 || lost > 0.5f) printf("t=%.1f drift=%.3e lost=%.3e\n", frame / 60.0, drift, lost);
    if (lost > 0.5f) {
      printf("falls at %.1f s\n", frame / 60.0);
      break;
    }
  }
  return 0;
}

/// Four unit boxes stacked light, heavy, light, heavy (bottom first; the
/// light ones 1 kg, the heavy ones `ratio` kg), 10 s: the top's greatest
/// sink and slide, as tests/world/test_substeps.cpp measures them; or two,
/// light under heavy, with `pair`.
static int stack(float ratio, bool pair) {
  world = make_world();
  add_box(b3_staticBody, (b3Vec3){0, -1, 0}, (b3Vec3){100, 1, 100}, 1);
  b3BodyId top = b3_nullBodyId;
  const int n = pair ? 2 : 4;
  for (int k = 0; k < n; ++k) top = add_box(b3_dynamicBody, (b3Vec3){0, 0.5f + k, 0}, (b3Vec3){0.5f, 0.5f, 0.5f}, k % 2 ? ratio : 1);
  const b3Pos start = b3Body_GetPosition(top);
  float sink = 0, slide = 0;
  for (int frame = 1; frame <= 600; ++frame) {
    b3World_Step(world, 1.0f / 60, 4);
    const b3Pos p = b3Body_GetPosition(top);
    sink = fmaxf(sink, start.y - p.y);
    slide = fmaxf(slide, hypotf(p.x - start.x, p.z - start.z));
  }
  printf("box3d stack 1:%g%s sink=%.3e slide=%.3e\n", ratio, pair ? " pair" : "", sink, slide);
  return 0;
}

/// The standard scene `name` built in `world`; its number of steps.
static int build(const char* name) {
  const bool large = strcmp(name, "large_pyramid") == 0;
  const float ground = large ? 400 : 100;
  add_box(b3_staticBody, (b3Vec3){0, -1, 0}, (b3Vec3){ground, 1, ground}, 1);
  const b3Vec3 cube = {0.5f, 0.5f, 0.5f};
  if (strcmp(name, "pile_nosleep") == 0) {
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j)
        for (int k = 0; k < 10; ++k)
          add_box(b3_dynamicBody, (b3Vec3){(i - 4.5f) * 1.2f, 1.0f + 1.2f * j, (k - 4.5f) * 1.2f}, cube, 1);
    return 600;
  }
  if (large || strcmp(name, "pyramid_nosleep") == 0) {
    const int base = large ? 100 : 20;
    for (int k = 0; k < base; ++k) {
      const int n = base - k;
      for (int i = 0; i < n; ++i) add_box(b3_dynamicBody, (b3Vec3){i - (n - 1) / 2.0f, 0.5f + k, 0}, cube, large ? 100 : 1);
    }
    return large ? 200 : 1200;
  }
  if (strcmp(name, "spheres_nosleep") == 0) {
    add_box(b3_staticBody, (b3Vec3){7.5f, 10, 0}, (b3Vec3){0.5f, 10, 8}, 1);
    add_box(b3_staticBody, (b3Vec3){-7.5f, 10, 0}, (b3Vec3){0.5f, 10, 8}, 1);
    add_box(b3_staticBody, (b3Vec3){0, 10, 7.5f}, (b3Vec3){8, 10, 0.5f}, 1);
    add_box(b3_staticBody, (b3Vec3){0, 10, -7.5f}, (b3Vec3){8, 10, 0.5f}, 1);
    const float density = 1.0f / (4.0f / 3.0f * 3.14159265f * 0.25f * 0.25f * 0.25f);  // mass 1
    uint32_t lcg = 12345u;
    for (int i = 0; i < 20; ++i)
      for (int j = 0; j < 25; ++j)
        for (int k = 0; k < 20; ++k) {
          lcg = lcg * 1664525u + 1013904223u;
          const float ux = (lcg >> 8) / 16777216.0f;
          lcg = lcg * 1664525u + 1013904223u;
          const float uz = (lcg >> 8) / 16777216.0f;
          add_sphere((b3Vec3){(i - 9.5f) * 0.6f + (ux - 0.5f) * 0.1f, 1.0f + 0.6f * j, (k - 9.5f) * 0.6f + (uz - 0.5f) * 0.1f},
                     0.25f, density);
        }
    return 600;
  }
  return 0;
}

int main(int argc, char** argv) {
  const char* name = argc > 1 ? argv[1] : "pile_nosleep";
  if (strcmp(name, "stack") == 0) return stack(argc > 2 ? (float)atof(argv[2]) : 1000, argc > 3 && strcmp(argv[3], "pair") == 0);
  if (strcmp(name, "tower") == 0) return tower(argc > 2 ? atoi(argv[2]) : 20, argc > 3 && strcmp(argv[3], "norecycle") == 0);
  world = make_world();
  const int steps = build(name);
  if (steps == 0) {
    fprintf(stderr, "usage: %s pile_nosleep | pyramid_nosleep | spheres_nosleep | large_pyramid | tower N [norecycle] | stack R [pair]\n",
            argv[0]);
    return 2;
  }
  double* times = malloc(sizeof(double) * (size_t)steps);
  for (int s = 0; s < steps; ++s) {
    const double start = now_ms();
    b3World_Step(world, 1.0f / 60, 4);
    times[s] = now_ms() - start;
  }
  const int timed = steps > 600 ? 300 : steps / 2;  // the last 300 steps, or the last half
  qsort(times + steps - timed, (size_t)timed, sizeof(double), by_value);
  printf("box3d %s %.4f ms/step\n", name, times[steps - timed + timed / 2]);
  free(times);
  b3DestroyWorld(world);
  return 0;
}
