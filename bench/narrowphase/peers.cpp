// bench/narrowphase/peers.cpp — the peers' cases of a pairing
// (cases.hpp): libccd's (IMPULSE_BENCH_HAVE_CCD) and Bullet's
// (IMPULSE_BENCH_HAVE_BULLET), each compiled in when the build found it.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "convex_pairs.hpp"

#ifdef IMPULSE_BENCH_HAVE_CCD
#include "ccd_shapes.hpp"
#endif
#ifdef IMPULSE_BENCH_HAVE_BULLET
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>
#endif

namespace narrowphase_bench {

namespace {

using namespace peers;

#ifdef IMPULSE_BENCH_HAVE_CCD
void add_ccd(std::vector<timed_case>& cases, const std::string& pair, const generated_pairs& g,
             const std::vector<std::size_t>& all, const std::vector<double>& reference,
             const std::vector<std::size_t>& separated, bool distance_row) {
  auto shapes = std::make_shared<std::vector<std::pair<ccd_shape, ccd_shape>>>();
  for (const pair_spec& p : g.pairs) shapes->push_back({ccd_shape(p.a), ccd_shape(p.b)});
  for (const bool tight : {false, true}) {
    const char* engine = tight ? "libccd_tight" : "libccd";
    ccd_t ccd = ccd_setup(1e-12);
    if (!tight) {  // CCD_INIT's tolerances and iteration limit
      ccd_t defaults;
      CCD_INIT(&defaults);
      ccd.max_iterations = defaults.max_iterations;
      ccd.epa_tolerance = defaults.epa_tolerance;
      ccd.mpr_tolerance = defaults.mpr_tolerance;
      ccd.dist_tolerance = defaults.dist_tolerance;
    }
    cases.push_back(make_case(pair, "gjk_epa", engine, all, reference, [shapes, ccd](std::size_t i) {
      const double depth = ccd_depth(ccd, (*shapes)[i].first, (*shapes)[i].second);
      return depth < 0 ? not_given : -depth;
    }));
    cases.push_back(make_case(pair, "mpr", engine, all, reference, [shapes, ccd](std::size_t i) {
      ccd_real_t depth = 0;
      ccd_vec3_t direction, position;
      if (ccdMPRPenetration(&(*shapes)[i].first, &(*shapes)[i].second, &ccd, &depth, &direction, &position) != 0)
        return not_given;
      return -double(depth);
    }));
    if (distance_row && !tight)
      cases.push_back(make_case(
          pair, "gjk_intersect", engine, separated, reference,
          [shapes, ccd](std::size_t i) { return double(ccdGJKIntersect(&(*shapes)[i].first, &(*shapes)[i].second, &ccd)); },
          false));  // a yes/no answer: no distance to compare
  }
}
#endif

#ifdef IMPULSE_BENCH_HAVE_BULLET
std::unique_ptr<btConvexShape> bullet_shape(const shape_spec& s) {
  std::unique_ptr<btConvexShape> shape;
  switch (s.kind) {
    case shape_kind::sphere: shape = std::make_unique<btSphereShape>(btScalar(s.radius)); break;
    case shape_kind::capsule:  // along y, as ours; its radius is its margin
      shape = std::make_unique<btCapsuleShape>(btScalar(s.radius), btScalar(2 * s.half_height));
      break;
    case shape_kind::box:
      shape = std::make_unique<btBoxShape>(btVector3(btScalar(s.half_extents.x), btScalar(s.half_extents.y),
                                                     btScalar(s.half_extents.z)));
      shape->setMargin(0);  // keeps the extents (btBoxShape::setMargin)
      break;
    case shape_kind::hull: {
      auto hull = std::make_unique<btConvexHullShape>();
      for (const v3& p : s.points) hull->addPoint(btVector3(btScalar(p.x), btScalar(p.y), btScalar(p.z)), false);
      hull->recalcLocalAabb();
      hull->setMargin(0);
      shape = std::move(hull);
      break;
    }
  }
  return shape;
}

btTransform bullet_pose(const shape_spec& s) {
  const auto& q = s.pose.rotation;
  const auto& p = s.pose.position;
  return btTransform(btQuaternion(btScalar(q.x), btScalar(q.y), btScalar(q.z), btScalar(q.w)),
                     btVector3(btScalar(p.x), btScalar(p.y), btScalar(p.z)));
}

/// btBoxBoxDetector reports up to four points through a Result: keep the
/// deepest (its depth is negative when they overlap).
struct deepest_point : btDiscreteCollisionDetectorInterface::Result {
  btScalar depth = BT_LARGE_FLOAT;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3&, const btVector3&, btScalar d) override { depth = std::min(depth, d); }
};

struct bullet_pair {
  std::unique_ptr<btConvexShape> a, b;
  btTransform pose_a, pose_b;
};

void add_bullet(std::vector<timed_case>& cases, const std::string& pair, const generated_pairs& g,
                const std::vector<std::size_t>& all, const std::vector<double>& reference,
                const std::vector<std::size_t>& separated, bool distance_row, bool boxes) {
  auto shapes = std::make_shared<std::vector<bullet_pair>>();
  for (const pair_spec& p : g.pairs)
    shapes->push_back({bullet_shape(p.a), bullet_shape(p.b), bullet_pose(p.a), bullet_pose(p.b)});
  const auto gjk = [shapes](std::size_t i) {
    const bullet_pair& p = (*shapes)[i];
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    btGjkPairDetector detector(p.a.get(), p.b.get(), &simplex, &epa);
    btDiscreteCollisionDetectorInterface::ClosestPointInput input;
    input.m_transformA = p.pose_a;
    input.m_transformB = p.pose_b;
    btPointCollector out;
    detector.getClosestPoints(input, out, nullptr);
    return out.m_hasResult ? double(out.m_distance) : not_given;
  };
  cases.push_back(make_case(pair, "gjk_epa", "bullet", all, reference, gjk));
  if (distance_row) cases.push_back(make_case(pair, "gjk_distance", "bullet", separated, reference, gjk));
  if (boxes)
    cases.push_back(make_case(pair, "box_box", "bullet", all, reference, [shapes, &g](std::size_t i) {
      const bullet_pair& p = (*shapes)[i];
      btBoxBoxDetector detector(static_cast<const btBoxShape*>(p.a.get()), static_cast<const btBoxShape*>(p.b.get()));
      btDiscreteCollisionDetectorInterface::ClosestPointInput input;
      input.m_transformA = p.pose_a;
      input.m_transformB = p.pose_b;
      deepest_point out;
      detector.getClosestPoints(input, out, nullptr);
      if (out.depth == BT_LARGE_FLOAT) return g.answers[i].overlapping ? 0.0 : not_given;
      return double(out.depth);
    }));
}
#endif

}  // namespace

void add_peers([[maybe_unused]] std::vector<timed_case>& cases, [[maybe_unused]] const std::string& pair,
               [[maybe_unused]] const generated_pairs& g, [[maybe_unused]] const std::vector<std::size_t>& all,
               [[maybe_unused]] const std::vector<double>& reference,
               [[maybe_unused]] const std::vector<std::size_t>& separated, [[maybe_unused]] bool distance_row,
               [[maybe_unused]] bool boxes) {
#ifdef IMPULSE_BENCH_HAVE_CCD
  add_ccd(cases, pair, g, all, reference, separated, distance_row);
#endif
#ifdef IMPULSE_BENCH_HAVE_BULLET
  add_bullet(cases, pair, g, all, reference, separated, distance_row, boxes);
#endif
}

}  // namespace narrowphase_bench
