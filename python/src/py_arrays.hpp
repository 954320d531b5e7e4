#pragma once
// NumPy arrays in and out: 2-D image views that borrow the array's memory when its layout allows
// (uint8 rows with unit column stride, any row stride), otherwise a C-contiguous copy.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "trn/image.hpp"
#include "trn/scoring.hpp"
#include "trn/template_view.hpp"

namespace trn::py {

namespace pyb = pybind11;

// A view plus the array that owns its pixels (the argument itself, or a copy); keep both alive
// while the view is used.
struct BorrowedGray {
    pyb::array owner;
    GrayView view;
};
struct BorrowedTemplate {
    pyb::array owner;
    TemplateView view;
};

// uint8 2-D image (ValueError naming `what` otherwise).
BorrowedGray gray_view(const pyb::handle& image, const char* what);
// uint8 or float32 2-D template; other float types are converted to float32 (a copy).
BorrowedTemplate template_view(const pyb::handle& image, const char* what);
// A new (height, width) uint8 array holding a copy of `image`.
pyb::array_t<std::uint8_t> gray_array(GrayView image);
// (N, 4) poses x, y, yaw, scale (any real dtype; copied).
std::vector<Pose> poses_from(const pyb::handle& poses);

}  // namespace trn::py
