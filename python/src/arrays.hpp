// arrays.hpp - numpy arrays in and out of the Python module: checked conversions, and vectors handed over uncopied.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

namespace facet::python {

namespace py = pybind11;

[[noreturn]] inline void value_error(const std::string& message) { throw py::value_error(message); }

// A Python integer (anything with __index__, not a float) within [lo, hi]; raises ValueError naming `name`
// otherwise, however large the integer.
inline long long integer_in(py::handle value, const std::string& name, long long lo, long long hi) {
  const py::object index = py::reinterpret_steal<py::object>(PyNumber_Index(value.ptr()));
  if (!index) {
    PyErr_Clear();
    value_error(name + ": expected an integer");
  }
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(index.ptr(), &overflow);
  if (overflow || v < lo || v > hi)
    value_error(name + ": expected " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " +
                py::str(index).cast<std::string>());
  return v;
}

// The text of a dtype, for messages ("float64", "<U1").
inline std::string dtype_name(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

// obj as a C-ordered array of T, converted from any dtype whose kind is in `kinds` ("f" floats, "i" "u" integers,
// "b" booleans) and any memory order, with `dims` dimensions (the last of `columns` values when given). Raises
// ValueError naming `name` otherwise.
template <class T>
py::array_t<T, py::array::c_style | py::array::forcecast> checked_array(
    py::handle obj, const std::string& name, const char* kinds, int dims,
    std::initializer_list<py::ssize_t> columns = {}) {
  py::array a = py::array::ensure(obj);
  if (!a) value_error(name + ": expected an array of numbers");
  if (std::string(kinds).find(a.dtype().kind()) == std::string::npos)
    value_error(name + ": dtype " + dtype_name(a) + " is not allowed here");
  if (a.ndim() != dims) {
    std::string shape = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? ", " : "") + std::to_string(a.shape(d));
    value_error(name + ": expected " + std::to_string(dims) + " dimensions, got shape " + shape + ")");
  }
  if (columns.size() && std::find(columns.begin(), columns.end(), a.shape(dims - 1)) == columns.end()) {
    std::string allowed;
    for (const py::ssize_t c : columns) allowed += (allowed.empty() ? "" : " or ") + std::to_string(c);
    value_error(name + ": the last dimension must be " + allowed + ", got " + std::to_string(a.shape(dims - 1)));
  }
  auto converted = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!converted) value_error(name + ": cannot convert dtype " + dtype_name(a));
  return converted;
}

// An N x C float array as glm vectors, every value finite.
template <int C>
std::vector<glm::vec<C, float>> finite_rows(py::handle obj, const std::string& name) {
  const auto a = checked_array<float>(obj, name, "fiub", 2, {C});
  const float* v = a.data();
  std::vector<glm::vec<C, float>> out(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < C; ++c) {
      const float x = v[i * C + static_cast<std::size_t>(c)];
      if (!std::isfinite(x)) value_error(name + ": row " + std::to_string(i) + " holds " + std::to_string(x));
      out[i][c] = x;
    }
  return out;
}

// A 4x4 matrix (a transform or pose) as glm's column-major mat4, every value finite.
inline glm::mat4 matrix4(py::handle obj, const std::string& name) {
  const auto a = checked_array<double>(obj, name, "fiu", 2, {4});
  if (a.shape(0) != 4) value_error(name + ": expected a 4x4 matrix");
  glm::mat4 m;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) {
      const double x = a.at(r, c);
      if (!std::isfinite(x)) value_error(name + ": holds a non-finite value");
      m[c][r] = static_cast<float>(x);
    }
  return m;
}

// Hands a vector to numpy without copying it: the array views the vector's storage and owns it through a capsule.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(std::move(shape), owner->data(), free_when_done);
}

}  // namespace facet::python
