#include "Arrays.h"

#include <cmath>
#include <limits>

namespace frugal::python {

namespace {

// "(4, 2)" as numpy prints a shape.
std::string shapeText(const py::array& array) {
    std::string out = "(";
    for (py::ssize_t d = 0; d < array.ndim(); ++d)
        out += (d ? ", " : "") + std::to_string(array.shape(d));
    return out + (array.ndim() == 1 ? ",)" : ")");
}

std::string dtypeText(const py::array& array) { return py::str(array.dtype()).cast<std::string>(); }

char kindOf(const py::array& array) { return array.dtype().kind(); }

// The object as a numpy array (a sequence is converted; what numpy cannot convert is refused).
py::array asArray(const py::handle& object, const std::string& what) {
    try {
        return py::module_::import("numpy").attr("asarray")(object);
    } catch (py::error_already_set& e) {
        throw InputError{what + ": not an array of numbers (" + std::string(e.what()) + ")"};
    }
}

void requireNumbers(const py::array& array, const std::string& what) {
    const char kind = kindOf(array);
    if (kind != 'f' && kind != 'i' && kind != 'u')
        throw InputError{what + ": dtype " + dtypeText(array) + " is not a number type (float or integer)"};
}

// The first NaN's flat position in a float array, or -1.
py::ssize_t firstNan(const py::array& array) {
    const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    const double* data = values.data();
    for (py::ssize_t i = 0; i < values.size(); ++i)
        if (std::isnan(data[i])) return i;
    return -1;
}

}  // namespace

template <int K>
std::vector<glm::vec<K, float>> vectorsFrom(const py::handle& object, const char* what) {
    const py::array array = asArray(object, what);
    requireNumbers(array, what);
    std::vector<glm::vec<K, float>> out;
    if (array.size() == 0 && array.ndim() <= 2) return out;
    if (array.ndim() != 2 || array.shape(1) != K)
        throw InputError{std::string(what) + ": expected an (N, " + std::to_string(K) + ") array, got shape " +
                         shapeText(array)};
    const auto values = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
    out.resize(std::size_t(array.shape(0)));
    std::memcpy(out.data(), values.data(), out.size() * sizeof(out[0]));
    return out;
}

template std::vector<glm::vec2> vectorsFrom<2>(const py::handle&, const char*);
template std::vector<glm::vec3> vectorsFrom<3>(const py::handle&, const char*);
template std::vector<glm::vec4> vectorsFrom<4>(const py::handle&, const char*);

std::vector<glm::vec4> colorsFrom(const py::handle& object) {
    const py::array array = asArray(object, "colors");
    if (array.ndim() != 2 || array.shape(1) != 3) return vectorsFrom<4>(array, "colors");
    std::vector<glm::vec4> out;
    for (const glm::vec3& rgb : vectorsFrom<3>(array, "colors")) out.emplace_back(rgb, 1.0f);
    return out;
}

std::vector<std::uint32_t> indicesFrom(const py::handle& object, py::ssize_t columns) {
    const std::string what = "indices";
    const py::array array = asArray(object, what);
    const char kind = kindOf(array);
    if (kind == 'f') {
        const py::ssize_t nan = firstNan(array);
        throw InputError{what + ": dtype " + dtypeText(array) + " is not an integer type" +
                         (nan >= 0 ? " (and index " + std::to_string(nan) + " is NaN)" : "")};
    }
    if (kind != 'i' && kind != 'u') throw InputError{what + ": dtype " + dtypeText(array) + " is not an integer type"};
    if (!(array.ndim() == 1 || (array.ndim() == 2 && array.shape(1) == columns)))
        throw InputError{what + ": expected a (T, " + std::to_string(columns) + ") or (" +
                         (columns == 1 ? std::string() : std::to_string(columns)) + "T,) array, got shape " +
                         shapeText(array)};
    std::vector<std::uint32_t> out(std::size_t(array.size()));
    constexpr auto kMax = std::numeric_limits<std::uint32_t>::max();
    const auto tooLarge = [&](std::size_t i, const std::string& value) {
        return InputError{what + ": index " + value + " (at " + std::to_string(i) + ") is larger than " +
                          std::to_string(kMax)};
    };
    if (kind == 'u') {
        const auto values = py::array_t<std::uint64_t, py::array::c_style | py::array::forcecast>::ensure(array);
        for (std::size_t i = 0; i < out.size(); ++i) {
            if (values.data()[i] > kMax) throw tooLarge(i, std::to_string(values.data()[i]));
            out[i] = std::uint32_t(values.data()[i]);
        }
        return out;
    }
    const auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
    for (std::size_t i = 0; i < out.size(); ++i) {
        const std::int64_t v = values.data()[i];
        if (v < 0) throw InputError{what + ": index " + std::to_string(v) + " (at " + std::to_string(i) + ") is negative"};
        if (v > std::int64_t(kMax)) throw tooLarge(i, std::to_string(v));
        out[i] = std::uint32_t(v);
    }
    return out;
}

glm::mat4 matrixFrom(const py::handle& object, const char* what) {
    const py::array array = asArray(object, what);
    requireNumbers(array, what);
    if (array.ndim() != 2 || array.shape(0) != 4 || array.shape(1) != 4)
        throw InputError{std::string(what) + ": expected a 4x4 matrix, got shape " + shapeText(array)};
    const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    glm::mat4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            const double v = values.data()[r * 4 + c];
            if (!std::isfinite(v))
                throw InputError{std::string(what) + ": row " + std::to_string(r) + ", column " + std::to_string(c) +
                                 " is " + py::str(py::float_(v)).cast<std::string>() + ", not finite"};
            m[c][r] = float(v);
        }
    return m;
}

py::array matrixArray(const glm::mat4& m) {
    py::array_t<float> out({4, 4});
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) out.mutable_at(r, c) = m[c][r];
    return out;
}

template <int K>
glm::vec<K, float> vectorFrom(const py::handle& object, const char* what) {
    const py::array array = asArray(object, what);
    requireNumbers(array, what);
    if (array.ndim() != 1 || array.shape(0) != K)
        throw InputError{std::string(what) + ": expected " + std::to_string(K) + " numbers, got shape " +
                         shapeText(array)};
    const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
    glm::vec<K, float> v;
    for (int k = 0; k < K; ++k) {
        if (!std::isfinite(values.data()[k]))
            throw InputError{std::string(what) + ": value " + std::to_string(k) + " is " +
                             py::str(py::float_(values.data()[k])).cast<std::string>() + ", not finite"};
        v[k] = float(values.data()[k]);
    }
    return v;
}

template glm::vec3 vectorFrom<3>(const py::handle&, const char*);
template glm::vec4 vectorFrom<4>(const py::handle&, const char*);

glm::vec4 colorFrom(const py::handle& object, const char* what) {
    const bool rgb = py::isinstance<py::sequence>(object) && !py::isinstance<py::str>(object) && py::len(object) == 3;
    return rgb ? glm::vec4(vectorFrom<3>(object, what), 1.0f) : vectorFrom<4>(object, what);
}

Pixels pixelsFrom(const py::handle& object) {
    const std::string what = "texture";
    const py::array array = asArray(object, what);
    if (array.dtype().kind() != 'u' || array.itemsize() != 1)
        throw InputError{what + ": dtype " + dtypeText(array) + " is not uint8 (8-bit RGBA or RGB)"};
    if (array.ndim() != 3 || (array.shape(2) != 3 && array.shape(2) != 4) || array.shape(0) < 1 || array.shape(1) < 1)
        throw InputError{what + ": expected an (H, W, 4) or (H, W, 3) array, got shape " + shapeText(array)};
    const auto values = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(array);
    Pixels out;
    out.height = int(std::min<py::ssize_t>(array.shape(0), std::numeric_limits<int>::max()));
    out.width = int(std::min<py::ssize_t>(array.shape(1), std::numeric_limits<int>::max()));
    const std::size_t pixels = std::size_t(array.shape(0)) * std::size_t(array.shape(1));
    const auto channels = std::size_t(array.shape(2));
    out.rgba.resize(pixels * 4);
    for (std::size_t i = 0; i < pixels; ++i) {
        for (std::size_t c = 0; c < channels; ++c) out.rgba[4 * i + c] = values.data()[channels * i + c];
        if (channels == 3) out.rgba[4 * i + 3] = 255;
    }
    return out;
}

template <class T>
py::array topFirstView(const T* data, int width, int height, int channels, py::object owner) {
    const auto size = py::ssize_t(sizeof(T));
    const py::ssize_t row = py::ssize_t(width) * channels * size;
    const T* top = data + std::size_t(height - 1) * std::size_t(width) * std::size_t(channels);
    std::vector<py::ssize_t> shape{height, width}, strides{-row, channels * size};
    if (channels > 1) {
        shape.push_back(channels);
        strides.push_back(size);
    }
    return py::array(py::dtype::of<T>(), shape, strides, top, owner);
}

template py::array topFirstView<std::uint8_t>(const std::uint8_t*, int, int, int, py::object);
template py::array topFirstView<std::uint32_t>(const std::uint32_t*, int, int, int, py::object);
template py::array topFirstView<float>(const float*, int, int, int, py::object);

}  // namespace frugal::python
