// bench/broadphase/bullet_broad_phases.hpp — Bullet's broad phases behind
// the few calls the benchmark makes, so that they replay exactly the same
// boxes and moves as ours.
//
// A step is setAabb for each box that moved, then calculateOverlappingPairs:
// what btCollisionWorld::performDiscreteCollisionDetection does before the
// narrow phase. Bullet's pair cache keeps fat pairs (btDbvtBroadphase's
// leaves are the boxes grown by gDbvtMargin = 0.05 m and by its motion
// prediction; btAxisSweep3 quantises the boxes outwards to 16 or 32 bits
// within the world bounds), so its pair counts are at least ours, which are
// exact.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <btBulletCollisionCommon.h>

#include "moving_boxes.hpp"
#include "peers.hpp"

namespace bench {

class bullet_broad_phase final : public broad_phase_driver {
 public:
  enum class kind { dbvt, axis_sweep };

  bullet_broad_phase(kind k, const box& bounds, std::size_t capacity)
      : dispatcher_(&configuration_) {
    const btVector3 lo(bounds.lower.x, bounds.lower.y, bounds.lower.z), hi(bounds.upper.x, bounds.upper.y, bounds.upper.z);
    if (k == kind::dbvt) {
      broad_phase_ = std::make_unique<btDbvtBroadphase>();
    } else if (capacity < 16000) {  // btAxisSweep3's 16-bit handles stop at 32767 ends
      broad_phase_ = std::make_unique<btAxisSweep3>(lo, hi, static_cast<unsigned short>(capacity + 1));
    } else {
      broad_phase_ = std::make_unique<bt32BitAxisSweep3>(lo, hi, static_cast<unsigned int>(capacity + 1));
    }
  }
  ~bullet_broad_phase() override {
    for (btBroadphaseProxy* p : proxies_) broad_phase_->destroyProxy(p, &dispatcher_);
  }
  bullet_broad_phase(const bullet_broad_phase&) = delete;
  bullet_broad_phase& operator=(const bullet_broad_phase&) = delete;

  void create(const box& b) override {
    proxies_.push_back(broad_phase_->createProxy(to_bullet(b.lower), to_bullet(b.upper), BOX_SHAPE_PROXYTYPE, nullptr,
                                                 1, -1, &dispatcher_));
  }
  void move(std::uint32_t i, const box& b) override {
    broad_phase_->setAabb(proxies_[i], to_bullet(b.lower), to_bullet(b.upper), &dispatcher_);
  }
  void update() override { broad_phase_->calculateOverlappingPairs(&dispatcher_); }
  [[nodiscard]] std::size_t pair_count() const override {
    return std::size_t(broad_phase_->getOverlappingPairCache()->getNumOverlappingPairs());
  }

 private:
  static btVector3 to_bullet(const vec& v) { return btVector3(v.x, v.y, v.z); }

  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broad_phase_;
  std::vector<btBroadphaseProxy*> proxies_;
};

}  // namespace bench
