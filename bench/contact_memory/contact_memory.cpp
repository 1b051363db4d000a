// contact_memory — bytes per overlapping pair, counted at the allocator.
//
// n unit boxes (half-extent 0.5, 1 kg) are created 1 mm apart along x, so
// every one of the n(n−1)/2 pairs overlaps and touches; then one step of
// 1/60 s. Printed per engine and n: the bytes the world held before the
// step, the peak during it and what it held after, and the peak's growth
// over the pairs. The counts are exact (every operator new and every
// Bullet allocation goes through the counters below), so the figures are
// the same on any run of the same build.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <string_view>
#include <vector>

#include "impulse/world.hpp"
#include "peers.hpp"

// ---- counting every allocation ----

std::size_t contact_memory::held = 0, contact_memory::peak = 0;

namespace {
/// Each block carries its size in front of it, so that free can count it.
constexpr std::size_t header = 64;  // keeps any alignment up to 64 bytes
}  // namespace

void* contact_memory::counted_alloc(std::size_t size, std::size_t align) {
  if (align > header) std::abort();
  auto* base = static_cast<unsigned char*>(std::aligned_alloc(header, (size + 2 * header - 1) / header * header));
  if (base == nullptr) throw std::bad_alloc();
  *reinterpret_cast<std::size_t*>(base) = size;
  held += size;
  if (held > peak) peak = held;
  return base + header;
}
void contact_memory::counted_free(void* p) noexcept {
  if (p == nullptr) return;
  unsigned char* base = static_cast<unsigned char*>(p) - header;
  held -= *reinterpret_cast<std::size_t*>(base);
  std::free(base);
}

using contact_memory::counted_alloc;
using contact_memory::counted_free;

void* operator new(std::size_t size) { return counted_alloc(size); }
void* operator new[](std::size_t size) { return counted_alloc(size); }
void* operator new(std::size_t size, std::align_val_t align) { return counted_alloc(size, std::size_t(align)); }
void* operator new[](std::size_t size, std::align_val_t align) { return counted_alloc(size, std::size_t(align)); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { counted_free(p); }

namespace {

using contact_memory::figures;
using contact_memory::held;
using contact_memory::peak;

void print(const char* engine, int n, const figures& f) {
  const double pairs = double(n) * double(n - 1) / 2;
  std::printf("| %s | %d | %.0f | %zu | %.0f | %.0f | %.0f |\n", engine, n, pairs, f.touching,
              double(f.before) / 1024, double(f.peak) / 1024, double(f.peak - f.before) / pairs);
}

template <class Config>
figures impulse_heap(int n) {
  using T = typename Config::scalar;
  held = peak = 0;
  figures f{};
  {
    impulse::world<Config> world;
    for (int i = 0; i < n; ++i) {
      impulse::body_def<T> d;
      d.pose.position = {T(0.001) * T(i), T(5), T(0)};
      d.mass = 1;
      world.create_body(d, impulse::box<T>::make({T(0.5), T(0.5), T(0.5)}));
    }
    f.before = held;
    peak = held;
    world.step(T(1) / T(60));
    f.peak = peak;
    f.after = held;
    f.touching = world.touching_pair_count();
  }
  return f;
}


}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::string_view(argv[1]) == "--quick";
  std::printf("| engine | boxes | pairs | touching | before, KiB | peak in the step, KiB | bytes per pair |\n");
  std::printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: |\n");
  const std::vector<int> sizes = quick ? std::vector<int>{100, 300} : std::vector<int>{100, 300, 1000};
  for (const int n : sizes) {
    print("impulse, float", n, impulse_heap<impulse::default_config>(n));
    print("impulse, double", n, impulse_heap<impulse::default_double_config>(n));
    if (const std::optional<figures> bullet = contact_memory::bullet_heap(n)) print("Bullet 3 (float)", n, *bullet);
  }
}
