// Small 3-vector helpers on std::array<double, 3> (layer a).
#pragma once

#include <array>
#include <cmath>

namespace cracklip::vec3
{
using V = std::array<double, 3>;

inline V add(const V& a, const V& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline V sub(const V& a, const V& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline V scale(double s, const V& a) { return {s * a[0], s * a[1], s * a[2]}; }
/// a + s b
inline V axpy(const V& a, double s, const V& b) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }
inline double dot(const V& a, const V& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V cross(const V& a, const V& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const V& a) { return std::hypot(a[0], a[1], a[2]); }
inline double dist(const V& a, const V& b) { return norm(sub(a, b)); }
/// a / |a| (a must be non-zero).
inline V unit(const V& a) { return scale(1.0 / norm(a), a); }

} // namespace cracklip::vec3
