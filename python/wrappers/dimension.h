// Bindings written once for both dimensions: the dimension comes from the
// mesh arrays at run time (as in DOLFINx), and one call site instantiates
// the C++ template of that dimension.
#pragma once

#include "array.h"

#include "geometry/crack_geometry.h"
#include "quadrature/cell_quadrature.h"

#include <pybind11/stl.h>

#include <string>
#include <type_traits>
#include <vector>

namespace cracklip_wrappers
{

/// The dimension of a mesh given as node coordinates x (n, dim) and cells
/// (m, dim + 1): 2 (triangles) or 3 (tetrahedra); ValueError otherwise.
inline int mesh_dimension(const carray<double>& x, const carray<std::int32_t>& cells)
{
  if (x.ndim() != 2 or (x.shape(1) != 2 and x.shape(1) != 3))
    throw std::invalid_argument("x (node coordinates) must be an array of shape (n, 2) or (n, 3)");
  const auto dim = static_cast<int>(x.shape(1));
  require_columns(cells, dim + 1, dim == 2 ? "cells (node indices per triangle)"
                                           : "cells (node indices per tetrahedron)");
  return dim;
}

/// f(std::integral_constant<int, dim>{}) for dim 2 or 3.
template <typename F>
decltype(auto) with_dimension(int dim, F&& f)
{
  if (dim == 2)
    return f(std::integral_constant<int, 2>{});
  if (dim != 3)
    throw std::invalid_argument("the dimension must be 2 or 3, got " + std::to_string(dim));
  return f(std::integral_constant<int, 3>{});
}

/// o cast to T, or ValueError(`what`) if it is something else.
template <typename T>
T cast_or_refuse(const py::handle& o, const char* what)
{
  try
  {
    return o.cast<T>();
  }
  catch (const py::cast_error&)
  {
    throw std::invalid_argument(what);
  }
}

/// A Python list of crack geometries of dimension dim (CrackGeometry or
/// CrackGeometry3D), as the C++ kernels take them.
template <int dim>
std::vector<const cracklip::CrackGeometryOf<dim>*> cracks_of(const py::sequence& cracks)
{
  return cast_or_refuse<std::vector<const cracklip::CrackGeometryOf<dim>*>>(
      cracks, dim == 2 ? "cracks must be a list of CrackGeometry (compute_crack_geometry) on a triangle mesh"
                       : "cracks must be a list of CrackGeometry3D (compute_crack_geometry_3d) on a tetrahedral mesh");
}

/// One crack geometry of dimension dim.
template <int dim>
const cracklip::CrackGeometryOf<dim>& crack_of(const py::object& geometry)
{
  return cast_or_refuse<const cracklip::CrackGeometryOf<dim>&>(
      geometry, dim == 2 ? "geometry must be a CrackGeometry (compute_crack_geometry) on a triangle mesh"
                         : "geometry must be a CrackGeometry3D (compute_crack_geometry_3d) on a tetrahedral mesh");
}

/// Quadrature options of dimension dim (QuadratureOptions or
/// QuadratureOptions3D).
template <int dim>
const cracklip::QuadratureOptionsOf<dim>& options_of(const py::object& options)
{
  return cast_or_refuse<const cracklip::QuadratureOptionsOf<dim>&>(
      options, dim == 2 ? "options must be QuadratureOptions on a triangle mesh"
                        : "options must be QuadratureOptions3D on a tetrahedral mesh");
}

} // namespace cracklip_wrappers
