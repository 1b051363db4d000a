// impulse/core/batch.hpp — batch<T, W>: W lanes of float or double as one value.
//
// The particle kernels are written once against batch<T, W> and compile to
// SIMD for every W, and to plain scalar code for W = 1, giving the same
// results within rounding (the lanes never interact). Lanes are GCC/Clang
// vector extensions (`vector_size`), which both compilers lower to the widest
// registers the target has and split when W is wider than the target.
//
// Why not <experimental/simd> or <immintrin.h>: measured on this project's
// machine (g++ 12, clang 14, -O0 -march=native), including
// <experimental/simd> costs 2.4–3.4 s and <immintrin.h> 0.6–0.8 s per
// translation unit; this header costs nothing measurable. And why not a plain
// loop left to the auto-vectoriser: a loop that calls std::sqrt vectorises
// only under -fno-math-errno, which a library cannot impose on its users (the
// same kernel runs 6–16× slower without it). Vector-extension arithmetic
// needs no such flag; square root, the one operation they lack, is the
// target's own instruction through the compiler builtin behind
// _mm*_sqrt_p[sd], with a lane-by-lane std::sqrt fallback on other targets.
#pragma once

#include <cmath>
#include <cstdint>
#include <type_traits>

#include "policy.hpp"

// Vectors wider than the target's registers are legal and split by the
// compiler; GCC and Clang warn (-Wpsabi) that such a vector passed by value
// would have a different ABI on a wider target. Every function here is
// inline, so no vector crosses an ABI boundary that could differ.
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace impulse {

namespace detail {

/// Width in bytes of the target's widest SIMD registers; 0 when the compiler
/// has no vector extensions (then every batch is scalar).
#if !defined(__GNUC__)
inline constexpr int simd_bytes = 0;
#elif defined(__AVX512F__)
inline constexpr int simd_bytes = 64;
#elif defined(__AVX__)
inline constexpr int simd_bytes = 32;
#elif defined(__SSE2__) || defined(__ARM_NEON)
inline constexpr int simd_bytes = 16;
#else
inline constexpr int simd_bytes = 0;
#endif

template <class T> struct mask_lane;
template <> struct mask_lane<float> { using type = std::int32_t; };
template <> struct mask_lane<double> { using type = std::int64_t; };

#if defined(__GNUC__)
template <class T, int W>
struct vector_of {
  typedef T type __attribute__((vector_size(sizeof(T) * W)));
};
#endif

/// Storage of W lanes: the scalar itself when W == 1.
template <class T, int W>
struct lanes_of {
  using type = typename vector_of<T, W>::type;
};
template <class T>
struct lanes_of<T, 1> {
  using type = T;
};

template <class T, int W>
using lanes = typename lanes_of<T, W>::type;

}  // namespace detail

/// Lanes per batch that fill the target's widest registers: 16 floats or 8
/// doubles with AVX-512, 8 or 4 with AVX, 4 or 2 with SSE2/NEON, else 1.
template <scalar_type T>
inline constexpr int native_width = detail::simd_bytes > 0 ? detail::simd_bytes / int(sizeof(T)) : 1;

/// A power of two from 1 to 16 lanes, at most 64 bytes (one AVX-512 register):
/// 16 floats or 8 doubles.
template <class T, int W>
concept batch_width = (W == 1 || W == 2 || W == 4 || W == 8 || W == 16) && W * sizeof(T) <= 64;

template <scalar_type T, int W>
  requires batch_width<T, W>
struct batch_mask;

template <scalar_type T, int W = native_width<T>>
  requires batch_width<T, W>
struct batch;

/// Result of comparing two batches: one boolean per lane.
template <scalar_type T, int W>
  requires batch_width<T, W>
struct batch_mask {
  // All-ones / all-zeros integer lanes, as vector comparisons produce; bool for W == 1.
  using native = std::conditional_t<W == 1, bool, detail::lanes<typename detail::mask_lane<T>::type, W>>;
  native v;

  friend batch_mask operator&(batch_mask a, batch_mask b) noexcept {
    if constexpr (W == 1) return {a.v && b.v};
    else return {a.v & b.v};
  }
  friend batch_mask operator|(batch_mask a, batch_mask b) noexcept {
    if constexpr (W == 1) return {a.v || b.v};
    else return {a.v | b.v};
  }
  friend batch_mask operator!(batch_mask a) noexcept {
    if constexpr (W == 1) return {!a.v};
    else return {a.v == 0};
  }

  bool operator[](int lane) const noexcept {
    if constexpr (W == 1) return v;
    else return v[lane] != 0;
  }
};

namespace detail {

/// Whether any lane of an all-ones/all-zeros integer vector is set: one
/// test instruction for 64 bytes (vptestmd, AVX-512) and 32 (vptest, AVX);
/// otherwise halves OR-ed together down to 16 bytes, then one byte-mask move
/// (pmovmskb), in place of W lane extractions and branches.
template <class I, int W>
bool any_lane_set(const lanes<I, W>& v) noexcept {
  constexpr int bytes = int(sizeof(I)) * W;
  if constexpr (W == 1) {
    return v != 0;
  }
#if defined(__AVX512F__) && !defined(__clang__)  // clang has no builtin for vptestmd; it folds the halves
  else if constexpr (bytes == 64) {
    using ints16 = int __attribute__((vector_size(64)));
    ints16 w;
    __builtin_memcpy(&w, &v, 64);
    return __builtin_ia32_ptestmd512(w, w, static_cast<unsigned short>(0xffff)) != 0;
  }
#endif
#if defined(__AVX__)
  else if constexpr (bytes == 32) {
    using longs4 = long long __attribute__((vector_size(32)));
    longs4 w;
    __builtin_memcpy(&w, &v, 32);
    return !__builtin_ia32_ptestz256(w, w);
  }
#endif
  else if constexpr (bytes > 16) {
    lanes<I, W / 2> half[2];
    __builtin_memcpy(half, &v, sizeof v);
    const lanes<I, W / 2> either = half[0] | half[1];
    return any_lane_set<I, W / 2>(either);
  }
#if defined(__SSE2__)
  else if constexpr (bytes == 16) {
    using bytes16 = char __attribute__((vector_size(16)));
    bytes16 b;
    __builtin_memcpy(&b, &v, 16);
    return __builtin_ia32_pmovmskb128(b) != 0;
  }
#endif
  else {
    for (int i = 0; i < W; ++i)
      if (v[i] != 0) return true;
    return false;
  }
}

}  // namespace detail

template <scalar_type T, int W>
bool any(batch_mask<T, W> m) noexcept {
  if constexpr (W == 1) return m.v;
  else return detail::any_lane_set<typename detail::mask_lane<T>::type, W>(m.v);
}
/// Whether a < b in any lane. Under AVX-512 the compare's mask register is
/// tested as it is (vcmpps, kortest), where any(a < b) first widens it to a
/// vector and tests that (two instructions more).
template <scalar_type T, int W>
bool any_less(const batch<T, W>& a, const batch<T, W>& b) noexcept {
#if defined(__AVX512F__)
  if constexpr (std::is_same_v<T, float> && W == 16)
    return __builtin_ia32_cmpps512_mask(a.v, b.v, 1 /* _CMP_LT_OS */, static_cast<unsigned short>(0xffff), 4) != 0;
  else if constexpr (std::is_same_v<T, double> && W == 8)
    return __builtin_ia32_cmppd512_mask(a.v, b.v, 1 /* _CMP_LT_OS */, static_cast<unsigned char>(0xff), 4) != 0;
  else
#endif
    return any(a < b);
}
template <scalar_type T, int W>
bool all(batch_mask<T, W> m) noexcept {
  return !any(!m);
}
template <scalar_type T, int W>
bool none(batch_mask<T, W> m) noexcept {
  return !any(m);
}

template <scalar_type T, int W>
  requires batch_width<T, W>
struct batch {
  using scalar = T;
  using mask = batch_mask<T, W>;
  using native = detail::lanes<T, W>;
  static constexpr int width = W;

  native v;

  /// s in every lane. As s − 0, which is s for every s, so compilers drop
  /// it; 0 + s is +0 for s = −0 and cost a scalar add before each broadcast.
  static batch broadcast(T s) noexcept {
    if constexpr (W == 1) return {s};
    else return {s - native{}};
  }
  /// W consecutive values from p (no alignment required).
  static batch load(const T* p) noexcept {
    batch b;
    __builtin_memcpy(&b.v, p, sizeof(native));
    return b;
  }
  /// Lane i takes base[index[i]].
  template <class Index>
  static batch gather(const T* base, const Index* index) noexcept {
    batch b;
    for (int i = 0; i < W; ++i) b.set(i, base[index[i]]);
    return b;
  }
  void store(T* p) const noexcept { __builtin_memcpy(p, &v, sizeof(native)); }

  T operator[](int lane) const noexcept {
    if constexpr (W == 1) return v;
    else return v[lane];
  }
  void set(int lane, T s) noexcept {
    if constexpr (W == 1) v = s;
    else v[lane] = s;
  }

  batch& operator+=(batch b) noexcept { v += b.v; return *this; }
  batch& operator-=(batch b) noexcept { v -= b.v; return *this; }
  batch& operator*=(batch b) noexcept { v *= b.v; return *this; }
  batch& operator/=(batch b) noexcept { v /= b.v; return *this; }

  friend batch operator-(batch a) noexcept { return {-a.v}; }
  friend batch operator+(batch a, batch b) noexcept { return {a.v + b.v}; }
  friend batch operator-(batch a, batch b) noexcept { return {a.v - b.v}; }
  friend batch operator*(batch a, batch b) noexcept { return {a.v * b.v}; }
  friend batch operator/(batch a, batch b) noexcept { return {a.v / b.v}; }
  friend batch operator+(batch a, T s) noexcept { return {a.v + s}; }
  friend batch operator-(batch a, T s) noexcept { return {a.v - s}; }
  friend batch operator*(batch a, T s) noexcept { return {a.v * s}; }
  friend batch operator/(batch a, T s) noexcept { return {a.v / s}; }
  friend batch operator+(T s, batch a) noexcept { return {s + a.v}; }
  friend batch operator-(T s, batch a) noexcept { return {s - a.v}; }
  friend batch operator*(T s, batch a) noexcept { return {s * a.v}; }
  friend batch operator/(T s, batch a) noexcept { return {s / a.v}; }

  friend mask operator<(batch a, batch b) noexcept { return {a.v < b.v}; }
  friend mask operator<=(batch a, batch b) noexcept { return {a.v <= b.v}; }
  friend mask operator>(batch a, batch b) noexcept { return {a.v > b.v}; }
  friend mask operator>=(batch a, batch b) noexcept { return {a.v >= b.v}; }
  friend mask operator==(batch a, batch b) noexcept { return {a.v == b.v}; }
  friend mask operator!=(batch a, batch b) noexcept { return {a.v != b.v}; }
};

/// Lane-wise m ? a : b.
template <scalar_type T, int W>
batch<T, W> select(batch_mask<T, W> m, batch<T, W> a, batch<T, W> b) noexcept {
  return {m.v ? a.v : b.v};
}

template <scalar_type T, int W>
batch<T, W> min(batch<T, W> a, batch<T, W> b) noexcept {
  return {a.v < b.v ? a.v : b.v};
}
template <scalar_type T, int W>
batch<T, W> max(batch<T, W> a, batch<T, W> b) noexcept {
  return {a.v > b.v ? a.v : b.v};
}
template <scalar_type T, int W>
batch<T, W> abs(batch<T, W> a) noexcept {
  return {a.v < T(0) ? -a.v : a.v};
}

namespace detail {

/// Square root of every lane, in place, with the target's instruction.
/// Vectors wider than the registers are split in halves; targets without a
/// builtin fall back to std::sqrt per lane (correct, and the only case that
/// pays errno's cost). Works through a reference: GCC warns (-Wpsabi, at the
/// end of the translation unit, beyond any pragma) about a vector wider than
/// the target passed or returned by value, never about one behind a reference.
template <class T, int W>
void lane_sqrt(lanes<T, W>& a) noexcept {
  constexpr int bytes = int(sizeof(T)) * W;
  if constexpr (W == 1) {
    a = std::sqrt(a);
  }
#if defined(__AVX512F__)
  else if constexpr (bytes == 64 && std::is_same_v<T, float>) {
#if defined(__clang__)
    a = __builtin_ia32_sqrtps512(a, 4);  // 4 = _MM_FROUND_CUR_DIRECTION
#else
    a = __builtin_ia32_sqrtps512_mask(a, a, static_cast<unsigned short>(0xffff), 4);
#endif
  } else if constexpr (bytes == 64 && std::is_same_v<T, double>) {
#if defined(__clang__)
    a = __builtin_ia32_sqrtpd512(a, 4);
#else
    a = __builtin_ia32_sqrtpd512_mask(a, a, static_cast<unsigned char>(0xff), 4);
#endif
  }
#endif
#if defined(__AVX__)
  else if constexpr (bytes == 32 && std::is_same_v<T, float>) {
    a = __builtin_ia32_sqrtps256(a);
  } else if constexpr (bytes == 32 && std::is_same_v<T, double>) {
    a = __builtin_ia32_sqrtpd256(a);
  }
#endif
#if defined(__SSE2__)
  else if constexpr (bytes == 16 && std::is_same_v<T, float>) {
    a = __builtin_ia32_sqrtps(a);
  } else if constexpr (bytes == 16 && std::is_same_v<T, double>) {
    a = __builtin_ia32_sqrtpd(a);
  }
#endif
  else if constexpr (bytes > simd_bytes && simd_bytes > 0) {
    lanes<T, W / 2> half[2];
    __builtin_memcpy(half, &a, sizeof a);
    lane_sqrt<T, W / 2>(half[0]);
    lane_sqrt<T, W / 2>(half[1]);
    __builtin_memcpy(&a, half, sizeof a);
  } else {
    for (int i = 0; i < W; ++i) a[i] = std::sqrt(a[i]);
  }
}

}  // namespace detail

template <scalar_type T, int W>
batch<T, W> sqrt(batch<T, W> a) noexcept {
  detail::lane_sqrt<T, W>(a.v);
  return a;
}

namespace detail {

/// The hardware estimate of 1/√a for float lanes, in place: rsqrt14ps
/// (relative error ≤ 2⁻¹⁴) for 16 lanes under AVX-512, rsqrtps (≤ 1.5·2⁻¹²)
/// for 8 and 4; false when the target has none for this width. Without the
/// AVX-512 instruction 16 lanes went through two 8-lane halves and the
/// stack, and the particle kernel in float ran no faster than in double.
template <class T, int W>
bool lane_rsqrt_estimate(lanes<T, W>& a) noexcept {
  constexpr int bytes = int(sizeof(T)) * W;
  if constexpr (!std::is_same_v<T, float> || W == 1) {
    return false;
  }
#if defined(__AVX512F__)
  else if constexpr (bytes == 64) {
    a = __builtin_ia32_rsqrt14ps512_mask(a, a, static_cast<unsigned short>(0xffff));
    return true;
  }
#endif
#if defined(__AVX__)
  else if constexpr (bytes == 32) {
    a = __builtin_ia32_rsqrtps256(a);
    return true;
  }
#endif
#if defined(__SSE__)
  else if constexpr (bytes == 16) {
    a = __builtin_ia32_rsqrtps(a);
    return true;
  }
#endif
  else if constexpr (bytes > 16) {
    lanes<T, W / 2> half[2];
    __builtin_memcpy(half, &a, sizeof a);
    if (!lane_rsqrt_estimate<T, W / 2>(half[0])) return false;
    lane_rsqrt_estimate<T, W / 2>(half[1]);
    __builtin_memcpy(&a, half, sizeof a);
    return true;
  } else {
    return false;
  }
}

/// The relative accuracy of lane_rsqrt_estimate for W lanes of T on this
/// target, in bits, known at compile time: 14 for rsqrt14ps, 11 for rsqrtps
/// (1.5·2⁻¹² ≈ 2^-11.4), 0 where there is no estimate.
template <class T, int W>
constexpr int rsqrt_estimate_bits() noexcept {
  constexpr int bytes = int(sizeof(T)) * W;
  if constexpr (!std::is_same_v<T, float> || W == 1) {
    return 0;
  }
#if defined(__AVX512F__)
  else if constexpr (bytes == 64) {
    return 14;
  }
#endif
#if defined(__AVX__)
  else if constexpr (bytes == 32) {
    return 11;
  }
#endif
#if defined(__SSE__)
  else if constexpr (bytes == 16) {
    return 11;
  }
#endif
  else if constexpr (bytes > 16) {
    return rsqrt_estimate_bits<T, W / 2>();
  } else {
    return 0;
  }
}

/// Whether lane_rsqrt_estimate has an estimate for W lanes of T on this
/// target, known at compile time.
template <class T, int W>
constexpr bool has_rsqrt_estimate() noexcept {
  return rsqrt_estimate_bits<T, W>() > 0;
}

}  // namespace detail

/// 1/√a for positive, finite, normal a. Float lanes take the hardware
/// estimate and one Newton–Raphson step, y ← y·(3 − a·y²)/2, which squares
/// its relative error: an estimate within e = 1.5·2⁻¹² (rsqrtps; 2⁻¹⁴ for
/// AVX-512's rsqrt14ps) leaves (3/2)e² + e³/2, 2e-7, and the step's own
/// roundings add at most 3·2⁻²⁴, 3.8e-7 in all, the bound a test holds
/// (the worst found over 2^-100 … 2^100: 1.65e-7 on a Zen 4, 2.41e-7 on an
/// Ice Lake, whose estimates differ). That is the accuracy of the particle
/// forces that use it, at a fraction of a square root and a division. Double lanes (x86 has no estimate below
/// AVX-512) and W = 1 compute 1/sqrt(a), correctly rounded twice.
template <scalar_type T, int W>
batch<T, W> rsqrt(batch<T, W> a) noexcept {
  batch<T, W> y = a;
  if (detail::lane_rsqrt_estimate<T, W>(y.v)) return y * (T(1.5) - (a * T(0.5)) * y * y);
  return T(1) / sqrt(a);
}

}  // namespace impulse

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
