// numpy planes <-> FrameView: a picture in Python is a list of 2-D uint8 (8-bit) or uint16
// (9..16-bit) arrays, Y or Y, Cb, Cr. Arrays whose samples are contiguous along a row are
// used in place whatever their row stride (C-contiguous input is never copied); others
// are copied once into a C-contiguous array.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "filmgrain/frame.hpp"

namespace filmgrain::python {

namespace py = pybind11;

struct NumpyPicture {
    FrameView view;
    std::vector<py::array> arrays;  // keeps the planes (or their copies) alive
};

// `planes`: a 2-D array (grey) or a sequence of 1 or 3 of them. The chroma format comes
// from the plane sizes unless `chroma` ("420", "422", "444", "400") is given; bit_depth is
// 8 for uint8 and must be given for uint16. writable: the planes are written in place.
// Throws Error(kInvalidArgument) naming the plane and what is wrong.
NumpyPicture picture_from_planes(const py::object& planes, std::optional<int> bit_depth,
                                 const std::optional<std::string>& chroma, bool writable);
// New C-contiguous planes for a picture of `like`'s size and format at `bit_depth`.
NumpyPicture new_picture_like(const FrameView& like, int bit_depth);
py::list planes_list(const NumpyPicture& picture);

}  // namespace filmgrain::python
