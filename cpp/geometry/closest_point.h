// Closest points on segments and triangles in 3D (layer a).
#pragma once

#include "geometry/vec3.h"

#include <algorithm>

namespace cracklip
{

/// Parameter t in [0, 1] of the point of segment A-B nearest to p.
inline double closest_on_segment(const vec3::V& p, const vec3::V& A, const vec3::V& B)
{
  const vec3::V AB = vec3::sub(B, A);
  const double l2 = vec3::dot(AB, AB);
  return l2 > 0.0 ? std::clamp(vec3::dot(vec3::sub(p, A), AB) / l2, 0.0, 1.0) : 0.0;
}

/// Closest point on triangle (a, b, c) to p and its feature: 0 the face,
/// 1 + k the edge (v_k, v_k+1), 4 + k the vertex v_k (Voronoi regions of
/// the triangle's features, tested in the order vertices, edges, face).
struct TrianglePoint
{
  vec3::V c;
  int feature;
};

inline TrianglePoint closest_on_triangle(const vec3::V& p, const vec3::V& a, const vec3::V& b, const vec3::V& c)
{
  using namespace vec3;
  const V ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 and d2 <= 0.0)
    return {a, 4};
  const V bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 and d4 <= d3)
    return {b, 5};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0)
    return {axpy(a, d1 / (d1 - d3), ab), 1};
  const V cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 and d5 <= d6)
    return {c, 6};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0)
    return {axpy(a, d2 / (d2 - d6), ac), 3};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 and d4 - d3 >= 0.0 and d5 - d6 >= 0.0)
    return {axpy(b, (d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b)), 2};
  const double den = 1.0 / (va + vb + vc);
  return {axpy(axpy(a, vb * den, ab), vc * den, ac), 0};
}

} // namespace cracklip
