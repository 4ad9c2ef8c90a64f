// numpy <-> std::span/std::vector helpers shared by the bindings.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace cracklip_wrappers
{
namespace py = pybind11;

template <typename T>
using carray = py::array_t<T, py::array::c_style | py::array::forcecast>;

template <typename T>
std::span<const T> as_span(const carray<T>& a)
{
  return std::span<const T>(a.data(), static_cast<std::size_t>(a.size()));
}

/// Move a vector into a numpy array of the given shape (no copy).
template <typename T>
py::array_t<T> as_pyarray(std::vector<T>&& v, std::vector<py::ssize_t> shape)
{
  auto* data = new std::vector<T>(std::move(v));
  py::capsule free(data, [](void* p) { delete reinterpret_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, data->data(), free);
}

template <typename T>
py::array_t<T> as_pyarray(std::vector<T>&& v)
{
  const auto n = static_cast<py::ssize_t>(v.size());
  return as_pyarray(std::move(v), {n});
}

/// Raise ValueError unless `a` has shape (n, cols).
template <typename T>
void require_columns(const carray<T>& a, py::ssize_t cols, const std::string& name)
{
  if (a.ndim() != 2 or a.shape(1) != cols)
  {
    std::string shape;
    for (py::ssize_t d = 0; d < a.ndim(); ++d)
      shape += (d ? ", " : "") + std::to_string(a.shape(d));
    throw std::invalid_argument(name + " must be an array of shape (n, " + std::to_string(cols) + "), got shape ("
                                + shape + ")");
  }
}

} // namespace cracklip_wrappers
