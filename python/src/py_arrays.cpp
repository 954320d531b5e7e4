// Conversions between NumPy arrays and trnkit's image views and poses.
#include "py_arrays.hpp"

#include <algorithm>
#include <string>

namespace trn::py {
namespace {

std::string shape_text(const pyb::array& a) {
    std::string s = "(";
    for (pyb::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

pyb::array as_array(const pyb::handle& h, const char* what) {
    if (!pyb::isinstance<pyb::array>(h))
        throw pyb::type_error(std::string(what) + " must be a numpy array, not " + std::string(pyb::str(h.get_type().attr("__name__"))));
    pyb::array a = pyb::reinterpret_borrow<pyb::array>(h);
    if (a.ndim() != 2) throw pyb::value_error(std::string(what) + " must be 2-D (height, width), not of shape " + shape_text(a));
    if (a.shape(0) == 0 || a.shape(1) == 0) throw pyb::value_error(std::string(what) + " of shape " + shape_text(a) + " is empty");
    return a;
}

// The array itself when rows are contiguous and advance by a positive whole number of elements;
// otherwise a C-contiguous copy.
template <typename T>
pyb::array rows_of(const pyb::array& a) {
    const auto item = static_cast<pyb::ssize_t>(sizeof(T));
    if (a.strides(1) == item && a.strides(0) >= a.shape(1) * item && a.strides(0) % item == 0) return a;
    return pyb::array_t<T, pyb::array::c_style | pyb::array::forcecast>::ensure(a);
}

template <typename T>
ImageView<const T> view_of(const pyb::array& a) {
    return {static_cast<const T*>(a.data()), static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)),
            static_cast<std::ptrdiff_t>(a.strides(0) / static_cast<pyb::ssize_t>(sizeof(T)))};
}

void check_side(const pyb::array& a, const char* what) {
    for (int i = 0; i < 2; ++i)  // int views: the library checks the real limits, this only keeps sizes representable
        if (a.shape(i) > (1 << 30)) throw pyb::value_error(std::string(what) + " of shape " + shape_text(a) + " is too large");
}

}  // namespace

BorrowedGray gray_view(const pyb::handle& image, const char* what) {
    pyb::array a = as_array(image, what);
    if (!a.dtype().is(pyb::dtype::of<std::uint8_t>()))
        throw pyb::value_error(std::string(what) + " must have dtype uint8, not " + std::string(pyb::str(a.dtype())));
    check_side(a, what);
    pyb::array rows = rows_of<std::uint8_t>(a);
    return {rows, view_of<std::uint8_t>(rows)};
}

BorrowedTemplate template_view(const pyb::handle& image, const char* what) {
    pyb::array a = as_array(image, what);
    check_side(a, what);
    if (a.dtype().is(pyb::dtype::of<std::uint8_t>())) {
        pyb::array rows = rows_of<std::uint8_t>(a);
        return {rows, TemplateView(view_of<std::uint8_t>(rows))};
    }
    if (a.dtype().kind() != 'f')
        throw pyb::value_error(std::string(what) + " must have dtype uint8 or a float type, not " + std::string(pyb::str(a.dtype())));
    pyb::array rows = a.dtype().is(pyb::dtype::of<float>()) ? rows_of<float>(a)
                                                            : pyb::array_t<float, pyb::array::c_style | pyb::array::forcecast>::ensure(a);
    return {rows, TemplateView(view_of<float>(rows))};
}

std::vector<Pose> poses_from(const pyb::handle& poses) {
    auto a = pyb::array_t<float, pyb::array::c_style | pyb::array::forcecast>::ensure(poses);
    if (!a) {
        PyErr_Clear();
        throw pyb::type_error("poses must be an array-like of shape (N, 4): x, y, yaw, scale");
    }
    if (a.ndim() == 1 && a.shape(0) == 4)
        throw pyb::value_error("poses has shape (4,), a single pose: pass shape (1, 4), e.g. [pose] or pose[None] "
                               "(rows x, y, yaw, scale)");
    if (a.ndim() != 2 || a.shape(1) != 4)
        throw pyb::value_error("poses must have shape (N, 4): x, y, yaw, scale; got shape " + shape_text(a));
    std::vector<Pose> out(static_cast<std::size_t>(a.shape(0)));
    const float* p = a.data();
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = {p[4 * i], p[4 * i + 1], p[4 * i + 2], p[4 * i + 3]};
    return out;
}

pyb::array_t<std::uint8_t> gray_array(GrayView image) {
    pyb::array_t<std::uint8_t> a({image.height, image.width});
    for (int y = 0; y < image.height; ++y) std::copy_n(image.row(y), image.width, a.mutable_data(y, 0));
    return a;
}

}  // namespace trn::py
