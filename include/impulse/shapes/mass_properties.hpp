// impulse/shapes/mass_properties.hpp — mass, center of mass and inertia of solids.
//
// mass_properties holds what a rigid body needs of its shape: the mass, the
// center of mass in shape space, and the inertia tensor about that center.
// Closed forms for the primitive solids live with each shape; this file has
// the general polyhedron (Eberly, "Polyhedral Mass Properties (Revisited)",
// 2002, a streamlined form of Mirtich's surface integrals, JGT 1996), the
// parallel-axis shift and the sum of parts, from which compounds are built.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>

#include "../core/error.hpp"
#include "../math/mat3.hpp"
#include "../math/vec3.hpp"

namespace impulse {

template <scalar_type T>
struct mass_properties {
  T mass = T(0);              ///< kg
  vec3<T> center{};           ///< center of mass, m, in shape space
  mat3<T> inertia{};          ///< kg·m², about `center`, shape-space axes
};

namespace detail {

template <scalar_type T>
void require_density(T density) {
  if (!std::isfinite(density)) report_error(error_code::non_finite, "mass properties: density is not finite");
  if (!(density > T(0))) report_error(error_code::non_positive_mass, "mass properties: density must be positive");
}

/// Inertia of a point mass m at offset r about the origin: m·(|r|²·1 − r rᵀ).
template <scalar_type T>
mat3<T> point_inertia(T m, const vec3<T>& r) noexcept {
  return (mat3<T>::identity() * dot(r, r) - outer(r, r)) * m;
}

}  // namespace detail

/// The same body's inertia about a point `offset` away from its center of
/// mass (parallel-axis theorem, in tensor form).
template <scalar_type T>
mat3<T> inertia_about(const mass_properties<T>& p, const vec3<T>& point) noexcept {
  return p.inertia + detail::point_inertia(p.mass, p.center - point);
}

/// The part placed in its parent's space by a rotation (as a matrix) and a
/// translation: center moved, inertia rotated to R·I·Rᵀ.
template <scalar_type T>
mass_properties<T> transformed(const mass_properties<T>& p, const mat3<T>& rotation, const vec3<T>& translation) noexcept {
  return {p.mass, rotation * p.center + translation, rotation * p.inertia * transpose(rotation)};
}

/// Two parts as one body: masses add, the center is the mass-weighted mean,
/// and each part's inertia is carried to the common center.
template <scalar_type T>
mass_properties<T> combine(const mass_properties<T>& a, const mass_properties<T>& b) noexcept {
  mass_properties<T> sum;
  sum.mass = a.mass + b.mass;
  sum.center = (a.center * a.mass + b.center * b.mass) / sum.mass;
  sum.inertia = inertia_about(a, sum.center) + inertia_about(b, sum.center);
  return sum;
}

/// Mass properties of the closed, outward-oriented triangle mesh
/// (triangles wound counter-clockwise seen from outside) filled with
/// `density`. Integrated in double about the mean vertex, so a polyhedron far
/// from the origin loses no digits to cancellation.
template <scalar_type T>
mass_properties<T> polyhedron_mass_properties(std::span<const vec3<T>> vertices,
                                              std::span<const std::uint32_t> triangles, T density) {
  detail::require_density(density);
  if (vertices.empty() || triangles.size() < 12 || triangles.size() % 3 != 0)
    detail::report_error(error_code::degenerate_shape,
                         "polyhedron_mass_properties: needs at least 4 triangles (a closed mesh)");
  for (std::uint32_t i : triangles)
    if (i >= vertices.size())
      detail::report_error(error_code::out_of_range, "polyhedron_mass_properties: a triangle names a missing vertex");
  vec3<double> reference{};
  for (const vec3<T>& v : vertices) reference += vec3<double>{double(v.x), double(v.y), double(v.z)};
  reference = reference / double(vertices.size());
  auto at = [&](std::uint32_t i) {
    return vec3<double>{double(vertices[i].x), double(vertices[i].y), double(vertices[i].z)} - reference;
  };
  // Eberly's integrals of 1, x, y, z, x², y², z², xy, yz, zx over the solid,
  // each a sum over triangles of the face normal's component times a
  // polynomial in the corners (the divergence theorem).
  double integral[10] = {};
  auto sub = [](double w0, double w1, double w2, double& f1, double& f2, double& f3, double& g0, double& g1,
                double& g2) {
    const double t0 = w0 + w1, t1 = w0 * w0, t2 = t1 + w1 * t0;
    f1 = t0 + w2;
    f2 = t2 + w2 * f1;
    f3 = w0 * t1 + w1 * t2 + w2 * f2;
    g0 = f2 + w0 * (f1 + w0);
    g1 = f2 + w1 * (f1 + w1);
    g2 = f2 + w2 * (f1 + w2);
  };
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const vec3<double> p0 = at(triangles[t]), p1 = at(triangles[t + 1]), p2 = at(triangles[t + 2]);
    const vec3<double> d = cross(p1 - p0, p2 - p0);
    double f1x, f2x, f3x, g0x, g1x, g2x, f1y, f2y, f3y, g0y, g1y, g2y, f1z, f2z, f3z, g0z, g1z, g2z;
    sub(p0.x, p1.x, p2.x, f1x, f2x, f3x, g0x, g1x, g2x);
    sub(p0.y, p1.y, p2.y, f1y, f2y, f3y, g0y, g1y, g2y);
    sub(p0.z, p1.z, p2.z, f1z, f2z, f3z, g0z, g1z, g2z);
    integral[0] += d.x * f1x;
    integral[1] += d.x * f2x;
    integral[2] += d.y * f2y;
    integral[3] += d.z * f2z;
    integral[4] += d.x * f3x;
    integral[5] += d.y * f3y;
    integral[6] += d.z * f3z;
    integral[7] += d.x * (p0.y * g0x + p1.y * g1x + p2.y * g2x);
    integral[8] += d.y * (p0.z * g0y + p1.z * g1y + p2.z * g2y);
    integral[9] += d.z * (p0.x * g0z + p1.x * g1z + p2.x * g2z);
  }
  constexpr double scale[10] = {1.0 / 6,  1.0 / 24, 1.0 / 24, 1.0 / 24,  1.0 / 60,
                                1.0 / 60, 1.0 / 60, 1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (int i = 0; i < 10; ++i) integral[i] *= scale[i] * double(density);
  const double mass = integral[0];
  if (!(mass > 0))
    detail::report_error(error_code::degenerate_shape,
                         "polyhedron_mass_properties: the mesh encloses no volume (open, flat or inside out)");
  const vec3<double> c{integral[1] / mass, integral[2] / mass, integral[3] / mass};
  const double xx = integral[5] + integral[6] - mass * (c.y * c.y + c.z * c.z);
  const double yy = integral[4] + integral[6] - mass * (c.z * c.z + c.x * c.x);
  const double zz = integral[4] + integral[5] - mass * (c.x * c.x + c.y * c.y);
  const double xy = -(integral[7] - mass * c.x * c.y);
  const double yz = -(integral[8] - mass * c.y * c.z);
  const double zx = -(integral[9] - mass * c.z * c.x);
  mass_properties<T> p;
  p.mass = T(mass);
  p.center = vec3<T>{T(c.x + reference.x), T(c.y + reference.y), T(c.z + reference.z)};
  p.inertia = mat3<T>::from_rows({T(xx), T(xy), T(zx)}, {T(xy), T(yy), T(yz)}, {T(zx), T(yz), T(zz)});
  return p;
}

}  // namespace impulse
