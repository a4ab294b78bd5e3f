// numpy arrays in and out of the module: checked conversions of what a user passes (a wrong dtype
// or shape, a NaN or an index out of range is refused with the numbers, as frugal::Error), and
// views of a frame's images without a copy.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace frugal::python {

namespace py = pybind11;

// An error in the user's input, raised as frugal.InputError.
struct InputError {
    std::string message;
};

// An (N, K) array of real numbers (any float or integer dtype, or a nested sequence) as N vectors;
// `what` names it in errors: "positions: expected an (N, 3) array of numbers, got shape (4, 2)".
template <int K>
std::vector<glm::vec<K, float>> vectorsFrom(const py::handle& object, const char* what);

// Per-vertex colours: (N, 3) RGB (alpha 1) or (N, 4) RGBA.
std::vector<glm::vec4> colorsFrom(const py::handle& object);

// Indices of primitives of `columns` vertices (3: triangles, 2: segments, 1: points): a (T, columns)
// or (columns·T,) array of integers (any integer dtype, none negative, each below 2^32). A float
// array is refused even when its values are whole.
std::vector<std::uint32_t> indicesFrom(const py::handle& object, py::ssize_t columns = 3);

// A 4x4 matrix of finite numbers, row-major as numpy prints it (translation in the last column),
// as glm's column-major matrix.
glm::mat4 matrixFrom(const py::handle& object, const char* what);

// glm's column-major matrix as a 4x4 float32 array, row-major as numpy prints it.
py::array matrixArray(const glm::mat4& m);

// A vector of K finite numbers (a tuple, a list or an array).
template <int K>
glm::vec<K, float> vectorFrom(const py::handle& object, const char* what);

// A colour: 3 finite numbers (RGB, alpha 1) or 4 (RGBA).
glm::vec4 colorFrom(const py::handle& object, const char* what);

// A texture's pixels: (H, W, 4) or (H, W, 3) uint8, first row first (v = 0, as glTF), as RGBA.
struct Pixels {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;
};
Pixels pixelsFrom(const py::handle& object);

// A view of `data` (rows bottom-up, `channels` values a pixel) as an (height, width[, channels])
// array with the top row first, kept alive by `owner`: no copy (a negative row stride).
template <class T>
py::array topFirstView(const T* data, int width, int height, int channels, py::object owner);

}  // namespace frugal::python
