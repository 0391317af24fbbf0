#include "python/numpy_planes.hpp"

#include <cstdint>

#include "core/field_names.hpp"
#include "filmgrain/error.hpp"

namespace filmgrain::python {
namespace {

ChromaFormat parse_chroma(const std::string& s) {
    if (s == "420") return ChromaFormat::k420;
    if (s == "422") return ChromaFormat::k422;
    if (s == "444") return ChromaFormat::k444;
    if (s == "400") return ChromaFormat::k400;
    throw Error(ErrorCode::kInvalidArgument, "chroma '" + s + "' is not a chroma format (allowed 400, 420, 422, 444)");
}

ChromaFormat chroma_from_sizes(int w, int h, int cw, int ch) {
    for (ChromaFormat f : {ChromaFormat::k420, ChromaFormat::k422, ChromaFormat::k444})
        if (plane_width(f, 1, w) == cw && plane_height(f, 1, h) == ch) return f;
    throw Error(ErrorCode::kInvalidArgument, "chroma planes of " + std::to_string(cw) + "x" + std::to_string(ch) +
                                                 " fit no chroma format of a " + std::to_string(w) + "x" +
                                                 std::to_string(h) + " picture (4:2:0, 4:2:2, 4:4:4)");
}

}  // namespace

NumpyPicture picture_from_planes(const py::object& planes, std::optional<int> bit_depth,
                                 const std::optional<std::string>& chroma, bool writable) {
    std::vector<py::object> items;
    if (py::isinstance<py::array>(planes)) {
        items.push_back(planes);
    } else if (py::isinstance<py::sequence>(planes) && !py::isinstance<py::str>(planes)) {
        for (py::handle h : planes.cast<py::sequence>()) items.push_back(py::reinterpret_borrow<py::object>(h));
    } else {
        throw Error(ErrorCode::kInvalidArgument, "a picture is a 2-D numpy array or a list of 1 or 3 of them");
    }
    if (items.size() != 1 && items.size() != 3)
        throw Error(ErrorCode::kInvalidArgument,
                    "a picture has 1 or 3 planes, not " + std::to_string(items.size()));
    NumpyPicture pic;
    int itemsize = 0;
    for (std::size_t c = 0; c < items.size(); c++) {
        if (!py::isinstance<py::array>(items[c]))
            throw Error(ErrorCode::kInvalidArgument, std::string("plane ") + plane_name(c) + " is not a numpy array");
        py::array a = py::reinterpret_borrow<py::array>(items[c]);
        if (a.ndim() != 2)
            throw Error(ErrorCode::kInvalidArgument, std::string("plane ") + plane_name(c) + " has " +
                                                         std::to_string(a.ndim()) + " dimensions (a plane has 2)");
        const bool u8 = a.dtype().is(py::dtype::of<uint8_t>()), u16 = a.dtype().is(py::dtype::of<uint16_t>());
        if (!u8 && !u16)
            throw Error(ErrorCode::kInvalidArgument, std::string("plane ") + plane_name(c) + " has dtype " +
                                                         std::string(py::str(a.dtype())) + " (allowed uint8, uint16)");
        if (itemsize && int(a.itemsize()) != itemsize)
            throw Error(ErrorCode::kInvalidArgument, "planes mix uint8 and uint16");
        itemsize = int(a.itemsize());
        const bool in_place = a.strides(1) == a.itemsize() && (reinterpret_cast<std::uintptr_t>(a.data()) % a.itemsize() == 0) &&
                              (a.strides(0) % a.itemsize() == 0);
        if (writable && !a.writeable())
            throw Error(ErrorCode::kInvalidArgument, std::string("plane ") + plane_name(c) + " is read-only");
        if (!in_place) {
            if (writable)
                throw Error(ErrorCode::kInvalidArgument, std::string("plane ") + plane_name(c) +
                                                             ": in-place output needs samples contiguous along rows");
            a = py::array::ensure(a, py::array::c_style | py::array::forcecast);
        }
        pic.arrays.push_back(a);
    }
    const int depth = bit_depth ? *bit_depth : itemsize == 1 ? 8 : 0;
    if (itemsize == 2 && !bit_depth)
        throw Error(ErrorCode::kInvalidArgument, "bit_depth: uint16 planes need their bit depth (allowed 9..16)");
    if (itemsize == 1 && depth != 8)
        throw Error(ErrorCode::kInvalidArgument, "bit_depth = " + std::to_string(depth) + " for uint8 planes (allowed 8)");
    if (itemsize == 2 && (depth < 9 || depth > 16))
        throw Error(ErrorCode::kInvalidArgument, out_of_range_message("bit_depth", depth, 9, 16));
    FrameView& v = pic.view;
    v.bit_depth = depth;
    v.height = int(pic.arrays[0].shape(0));
    v.width = int(pic.arrays[0].shape(1));
    if (chroma) v.format = parse_chroma(*chroma);
    else if (pic.arrays.size() == 1) v.format = ChromaFormat::k400;
    else v.format = chroma_from_sizes(v.width, v.height, int(pic.arrays[1].shape(1)), int(pic.arrays[1].shape(0)));
    if (std::size_t(num_planes(v.format)) != pic.arrays.size())
        throw Error(ErrorCode::kInvalidArgument, "chroma " + std::string(chroma ? *chroma : "") + " has " +
                                                     std::to_string(num_planes(v.format)) + " plane(s), the picture " +
                                                     std::to_string(pic.arrays.size()));
    for (std::size_t c = 0; c < pic.arrays.size(); c++) {
        py::array& a = pic.arrays[c];
        PlaneView& p = v.planes[c];
        // read-only input is only read: the session writes dst, which is this array only in place
        p.data = static_cast<uint8_t*>(const_cast<void*>(a.data()));
        p.stride = a.strides(0);
        p.height = int(a.shape(0));
        p.width = int(a.shape(1));
        const int ew = plane_width(v.format, int(c), v.width), eh = plane_height(v.format, int(c), v.height);
        if (p.width != ew || p.height != eh)
            throw Error(ErrorCode::kInvalidArgument, std::string("plane ") + plane_name(c) + " is " +
                                                         std::to_string(p.width) + "x" + std::to_string(p.height) +
                                                         ", expected " + std::to_string(ew) + "x" + std::to_string(eh));
    }
    return pic;
}

NumpyPicture new_picture_like(const FrameView& like, int bit_depth) {
    NumpyPicture pic;
    pic.view = like;
    pic.view.bit_depth = bit_depth;
    for (int c = 0; c < like.plane_count(); c++) {
        const py::ssize_t h = like.planes[c].height, w = like.planes[c].width;
        py::array a = bit_depth > 8 ? py::array(py::array_t<uint16_t>({h, w})) : py::array(py::array_t<uint8_t>({h, w}));
        pic.view.planes[c].data = static_cast<uint8_t*>(a.mutable_data());
        pic.view.planes[c].stride = a.strides(0);
        pic.arrays.push_back(a);
    }
    return pic;
}

py::list planes_list(const NumpyPicture& picture) {
    py::list out;
    for (const py::array& a : picture.arrays) out.append(a);
    return out;
}

}  // namespace filmgrain::python
