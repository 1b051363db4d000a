// bench/scenes/ode_engine.hpp — ODE 0.16 behind the scenes benchmark's
// engine interface (engine.hpp), set up as a user gets it out of the box:
//
// - dWorldQuickStep with the world's defaults: 20 iterations, SOR
//   over-relaxation 1.3, constraint order shuffled every 8 iterations
//   (ODE's generator, reseeded to its initial 0 for every scene), global
//   ERP 0.2 and CFM (1e-10 in a double build, 1e-5 in a single one), no
//   contact surface layer, no cap on the correcting velocity, no damping.
// - one dHashSpace with the default levels (cells 2^-3 to 2^10 m, which
//   holds the 800 m ground of large_pyramid); static bodies are geoms with
//   no body in the same space.
// - contacts: dCollide with up to 4 points per pair (a box on a box gives
//   up to 8, culled to the 4 that span the largest area), each a contact
//   joint in a joint group emptied after the step. Surface: dContactApprox1
//   (the friction pyramid, each friction direction bounded by mu times the
//   normal impulse, rather than by a fixed force), mu = the spec's
//   effective friction, bounce = its restitution with bounce_vel 0.2 m/s
//   (choice: Bullet's m_restitutionVelocityThreshold, so both peers stop
//   bouncing at the same approach speed); soft_erp and soft_cfm not set,
//   so the world's ERP and CFM apply.
// - sleeping: the world's auto-disable (defaults: 10 steps below 0.01 m/s
//   and 0.01 rad/s) when the scene has it, off when it does not. Pairs in
//   which no body is enabled (static, or asleep) are skipped in the near
//   callback, which is what makes disabled bodies cheap; a contact with an
//   enabled body re-enables a disabled one in ODE's island step.
//
// ODE keeps no material per geom, so the near callback applies the standard
// scenes' combine directly: friction sqrt(f0·f1), restitution max(e0, e1).
//
// Precision: the adapter is written in dReal, so it builds against a
// single- or double-precision ODE; the constructor checks that the
// library was built with the precision the headers declare (a mismatch
// corrupts memory silently), and config() reports it.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <ode/ode.h>

#include "engine.hpp"
#include "scene_spec.hpp"

namespace bench::scenes {

namespace detail {

/// dInitODE2 once per process, dCloseODE at exit.
class ode_library {
 public:
  static void ensure_initialised() { static const ode_library library; }

  ode_library(const ode_library&) = delete;
  ode_library& operator=(const ode_library&) = delete;

 private:
  ode_library() {
    if (dInitODE2(0) == 0) throw std::runtime_error("ode: dInitODE2 failed");
    const bool double_headers = std::is_same_v<dReal, double>;
    const bool double_library = dCheckConfiguration("ODE_double_precision") == 1;
    if (double_headers != double_library)
      throw std::runtime_error(std::string("ode: the headers declare ") + (double_headers ? "double" : "single") +
                               " precision but the library was built with the other (" + dGetConfiguration() + ")");
  }
  ~ode_library() { dCloseODE(); }
};

}  // namespace detail

class ode_engine {
 public:
  static constexpr std::string_view name = "ode";

  /// Approach speed below which contacts do not bounce, m/s.
  static constexpr dReal bounce_threshold = 0.2;
  /// Contact points kept per pair of geoms.
  static constexpr int max_contacts_per_pair = 4;

  ode_engine() {
    detail::ode_library::ensure_initialised();
    world_ = dWorldCreate();
    space_ = dHashSpaceCreate(nullptr);
    contacts_ = dJointGroupCreate(0);
  }
  ~ode_engine() {
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // and the geoms in it (the default cleanup mode)
    dWorldDestroy(world_);  // and its bodies
  }
  ode_engine(const ode_engine&) = delete;
  ode_engine& operator=(const ode_engine&) = delete;

  [[nodiscard]] std::string config() const {
    return "quickstep iterations=" + std::to_string(dWorldGetQuickStepNumIterations(world_)) +
           (std::is_same_v<dReal, double> ? " double" : " single");
  }

  void build(const scene_spec& spec) {
    // dWorldQuickStep shuffles the constraint order every 8 iterations with
    // ODE's one global generator: reseeded, a scene's figures do not depend
    // on which scenes ran before it in the process.
    dRandSetSeed(0);
    dt_ = static_cast<dReal>(spec.dt);
    dWorldSetGravity(world_, dReal(spec.gravity.x), dReal(spec.gravity.y), dReal(spec.gravity.z));
    // Bodies take the world's auto-disable settings when created: set first.
    dWorldSetAutoDisableFlag(world_, spec.sleeping ? 1 : 0);
    // Sized once: geoms point at their material, which must not move.
    materials_.resize(spec.bodies.size());
    bodies_.assign(spec.bodies.size(), nullptr);
    geoms_.assign(spec.bodies.size(), nullptr);
    for (std::size_t i = 0; i < spec.bodies.size(); ++i) {
      const body_spec& b = spec.bodies[i];
      materials_[i] = b.surface;
      const dReal side_x = dReal(2 * b.half_extents.x), side_y = dReal(2 * b.half_extents.y),
                  side_z = dReal(2 * b.half_extents.z);
      dGeomID geom = b.shape == shape_kind::box ? dCreateBox(space_, side_x, side_y, side_z)
                                                : dCreateSphere(space_, dReal(b.radius));
      dGeomSetData(geom, &materials_[i]);
      dQuaternion q{dReal(b.orientation.w), dReal(b.orientation.x), dReal(b.orientation.y), dReal(b.orientation.z)};
      if (b.is_static) {
        dGeomSetPosition(geom, dReal(b.position.x), dReal(b.position.y), dReal(b.position.z));
        dGeomSetQuaternion(geom, q);
      } else {
        dBodyID body = dBodyCreate(world_);
        dMass mass;
        if (b.shape == shape_kind::box)
          dMassSetBoxTotal(&mass, dReal(b.mass), side_x, side_y, side_z);
        else
          dMassSetSphereTotal(&mass, dReal(b.mass), dReal(b.radius));
        dBodySetMass(body, &mass);
        dBodySetPosition(body, dReal(b.position.x), dReal(b.position.y), dReal(b.position.z));
        dBodySetQuaternion(body, q);
        dBodySetLinearVel(body, dReal(b.linear_velocity.x), dReal(b.linear_velocity.y), dReal(b.linear_velocity.z));
        dGeomSetBody(geom, body);
        bodies_[i] = body;
      }
      geoms_[i] = geom;
    }
    states_.resize(spec.bodies.size());
  }

  void step() {
    dSpaceCollide(space_, this, &near_callback);
    dWorldQuickStep(world_, dt_);
    dJointGroupEmpty(contacts_);
  }

  std::span<const body_state> states() {
    for (std::size_t i = 0; i < geoms_.size(); ++i) {
      if (dBodyID body = bodies_[i]) {
        const dReal* p = dBodyGetPosition(body);
        const dReal* q = dBodyGetQuaternion(body);
        const dReal* v = dBodyGetLinearVel(body);
        const dReal* w = dBodyGetAngularVel(body);
        states_[i] = {{p[0], p[1], p[2]}, {q[0], q[1], q[2], q[3]}, {v[0], v[1], v[2]}, {w[0], w[1], w[2]},
                      dBodyIsEnabled(body) != 0};
      } else {
        const dReal* p = dGeomGetPosition(geoms_[i]);
        dQuaternion q;
        dGeomGetQuaternion(geoms_[i], q);
        states_[i] = {{p[0], p[1], p[2]}, {q[0], q[1], q[2], q[3]}, {}, {}, false};
      }
    }
    return states_;
  }

 private:
  static void near_callback(void* data, dGeomID a, dGeomID b) {
    auto& self = *static_cast<ode_engine*>(data);
    dBodyID body_a = dGeomGetBody(a), body_b = dGeomGetBody(b);
    const bool moving_a = body_a != nullptr && dBodyIsEnabled(body_a) != 0;
    const bool moving_b = body_b != nullptr && dBodyIsEnabled(body_b) != 0;
    if (!moving_a && !moving_b) return;  // static or asleep on both sides: nothing can change

    std::array<dContact, max_contacts_per_pair> contact{};
    const int n = dCollide(a, b, max_contacts_per_pair, &contact[0].geom, sizeof(dContact));
    if (n == 0) return;
    const material& ma = *static_cast<const material*>(dGeomGetData(a));
    const material& mb = *static_cast<const material*>(dGeomGetData(b));
    const auto friction = static_cast<dReal>(std::sqrt(ma.friction * mb.friction));
    const auto restitution = static_cast<dReal>(std::max(ma.restitution, mb.restitution));
    for (int i = 0; i < n; ++i) {
      dSurfaceParameters& s = contact[std::size_t(i)].surface;
      s.mode = dContactApprox1;
      s.mu = friction;
      if (restitution > 0) {
        s.mode |= dContactBounce;
        s.bounce = restitution;
        s.bounce_vel = bounce_threshold;
      }
      dJointID joint = dJointCreateContact(self.world_, self.contacts_, &contact[std::size_t(i)]);
      dJointAttach(joint, body_a, body_b);
    }
  }

  dWorldID world_ = nullptr;
  dSpaceID space_ = nullptr;
  dJointGroupID contacts_ = nullptr;
  std::vector<material> materials_;
  std::vector<dBodyID> bodies_;  // null for static bodies
  std::vector<dGeomID> geoms_;
  std::vector<body_state> states_;
  dReal dt_ = dReal(1) / 60;
};

static_assert(scene_engine<ode_engine>);

}  // namespace bench::scenes
