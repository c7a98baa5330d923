// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Explicit checks of the numpy arrays handed to the module: type, shape,
/// dtype, byte order, alignment and C-contiguity. A failed check is a
/// ValueError naming the argument and what to pass instead; nothing is ever
/// copied or converted silently.

#include "point_buffers.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>

namespace streamclust::python {

namespace py = pybind11;

/// The argument as a numpy array, or a ValueError.
inline py::array require_ndarray(const py::handle& obj, const char* name) {
  if (!py::isinstance<py::array>(obj)) {
    throw py::value_error(std::string(name) + ": expected a numpy.ndarray, got " +
                          std::string(py::str(py::type::handle_of(obj).attr("__name__"))) +
                          " (wrap it with numpy.asarray)");
  }
  return py::reinterpret_borrow<py::array>(obj);
}

/// C-contiguous and aligned, or a ValueError: the engine reads the buffer in place.
inline void require_c_contiguous(const py::array& a, const char* name) {
  const int flags = a.flags();
  if (!(flags & py::array::c_style)) {
    throw py::value_error(std::string(name) +
                          ": the array is not C-contiguous (a strided view or a transposed array); pass "
                          "numpy.ascontiguousarray(" + name + "), one copy made by you");
  }
  if (!(flags & py::detail::npy_api::NPY_ARRAY_ALIGNED_)) {
    throw py::value_error(std::string(name) + ": the array's buffer is not aligned; pass numpy.require(" + name +
                          ", requirements='CA')");
  }
}

inline std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

/// The points of xyz (N, 3) float32/float64, t (N,) float64 and optional
/// intensity (N,) float32/float64, checked, as raw buffers (no copy). The
/// arrays must outlive the buffers. `xyz_name` and `t_name` name the
/// arguments in the messages.
inline PointBuffers point_buffers(const py::handle& xyz_obj, const py::handle& t_obj, const py::handle& intensity_obj,
                                  const char* xyz_name = "xyz", const char* t_name = "t") {
  const std::string xn = xyz_name, tn = t_name;
  const py::array xyz = require_ndarray(xyz_obj, xyz_name);
  if (xyz.ndim() != 2 || xyz.shape(1) != 3) {
    throw py::value_error(xn + ": expected shape (N, 3), got " + shape_of(xyz));
  }
  PointBuffers b;
  b.size = static_cast<std::size_t>(xyz.shape(0));
  if (py::array_t<float>::check_(xyz)) {
    b.xyz32 = static_cast<const float*>(xyz.data());
  } else if (py::array_t<double>::check_(xyz)) {
    b.xyz64 = static_cast<const double*>(xyz.data());
  } else {
    throw py::value_error(xn + ": expected dtype float32 or float64 (native byte order), got " +
                          std::string(py::str(xyz.dtype())));
  }
  require_c_contiguous(xyz, xyz_name);

  const py::array t = require_ndarray(t_obj, t_name);
  if (t.ndim() != 1) throw py::value_error(tn + ": expected shape (N,), got " + shape_of(t));
  if (static_cast<std::size_t>(t.shape(0)) != b.size) {
    throw py::value_error(tn + ": " + std::to_string(t.shape(0)) + " times for " + std::to_string(b.size) +
                          " points (" + xn + "); expected one time per point");
  }
  if (!py::array_t<double>::check_(t)) {
    throw py::value_error(tn + ": expected dtype float64 seconds, got " + std::string(py::str(t.dtype())));
  }
  require_c_contiguous(t, t_name);
  b.t = static_cast<const double*>(t.data());

  if (!intensity_obj.is_none()) {
    const py::array in = require_ndarray(intensity_obj, "intensity");
    if (in.ndim() != 1) throw py::value_error("intensity: expected shape (N,), got " + shape_of(in));
    if (static_cast<std::size_t>(in.shape(0)) != b.size) {
      throw py::value_error("intensity: " + std::to_string(in.shape(0)) + " values for " + std::to_string(b.size) +
                            " points (xyz); expected one per point");
    }
    if (py::array_t<float>::check_(in)) {
      b.intensity32 = static_cast<const float*>(in.data());
    } else if (py::array_t<double>::check_(in)) {
      b.intensity64 = static_cast<const double*>(in.data());
    } else {
      throw py::value_error("intensity: expected dtype float32 or float64, got " + std::string(py::str(in.dtype())));
    }
    require_c_contiguous(in, "intensity");
  }
  return b;
}

}  // namespace streamclust::python
