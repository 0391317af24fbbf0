// filmgrain.Session: the one stream session (include/filmgrain/session.hpp) for Python.
// Metadata dicts are the JSON forms of the CLI's parameter files (named after the syntax
// elements); synthesis runs with the GIL released, one call at a time per session.
#include <pybind11/stl.h>

#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "filmgrain/session.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/fgc_json.hpp"
#include "metadata/fgc_sei.hpp"
#include "cli_common.hpp"
#include "python/numpy_planes.hpp"
#include "python/python_module.hpp"
#include "session/parameter_file_feed.hpp"

namespace filmgrain::python {
namespace {

// Python dicts travel as JSON text: one parser (the CLI's) for both.
nlohmann::json json_of(const py::dict& d) {
    const py::module_ json = py::module_::import("json");
    const std::string text = py::str(json.attr("dumps")(d));
    try {
        return nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        throw Error(ErrorCode::kInvalidArgument, std::string("parameters: ") + e.what());
    }
}

std::optional<FgcPictureIds> ids_of(std::optional<int> poc, int idr_pic_id) {
    if (!poc) return std::nullopt;
    return FgcPictureIds{*poc, idr_pic_id};
}

class PySession {
public:
    explicit PySession(const SessionOptions& o) : session_(o) {}

    void push_fgc_sei(const py::bytes& payload, const std::string& codec, std::optional<int> poc, int idr_pic_id) {
        const std::string b = payload;
        std::lock_guard<std::mutex> lock(mutex_);
        session_.receive_fgc_sei_payload(reinterpret_cast<const uint8_t*>(b.data()), b.size(), parse_fgc_codec(codec),
                                         ids_of(poc, idr_pic_id));
    }
    void push_fgc_params(const py::dict& params, const std::string& codec, std::optional<int> poc, int idr_pic_id) {
        const FgcParams p = fgc_params_from_json(json_of(params));
        std::lock_guard<std::mutex> lock(mutex_);
        session_.receive_fgc_params(p, parse_fgc_codec(codec), ids_of(poc, idr_pic_id));
    }
    void push_av1_params(const py::dict& params, unsigned refresh_frame_flags, int matrix_coefficients) {
        const Av1FilmGrainParams p = av1_params_from_json(json_of(params));
        std::lock_guard<std::mutex> lock(mutex_);
        session_.receive_av1_params(p, refresh_frame_flags, matrix_coefficients);
    }
    void show_existing_av1_frame(int idx) {
        std::lock_guard<std::mutex> lock(mutex_);
        session_.show_existing_av1_frame(idx);
    }
    void push_afgs1(const py::bytes& payload) {
        const std::string b = payload;
        std::lock_guard<std::mutex> lock(mutex_);
        session_.receive_afgs1_t35(reinterpret_cast<const uint8_t*>(b.data()), b.size());
    }
    void attach_files(std::optional<std::string> params, std::vector<std::string> sei, std::vector<std::string> afgs1,
                      std::optional<std::string> sei_codec, int matrix_coefficients, int fps_num, int fps_den) {
        session::ParameterFiles files;
        if (params) files.params = *params;
        files.sei = std::move(sei);
        files.afgs1 = std::move(afgs1);
        if (sei_codec) {
            files.sei_codec = parse_fgc_codec(*sei_codec);
            files.sei_codec_given = true;
        }
        files.matrix_coefficients = matrix_coefficients;
        if (fps_num <= 0 || fps_den <= 0)
            throw Error(ErrorCode::kInvalidArgument, "fps " + std::to_string(fps_num) + "/" + std::to_string(fps_den) +
                                                         " is not a frame rate (both positive)");
        auto feed = std::make_unique<session::ParameterFileFeed>(files);
        std::lock_guard<std::mutex> lock(mutex_);
        feed_ = std::move(feed);
        fps_num_ = fps_num;
        fps_den_ = fps_den;
        fed_pictures_ = 0;
    }
    void reset() {
        std::lock_guard<std::mutex> lock(mutex_);
        session_.reset();
        fed_pictures_ = 0;
    }

    FrameInfo info_for(std::optional<int> poc, int idr_pic_id, std::optional<uint32_t> seed,
                       std::optional<int> matrix_coefficients, bool* given) {
        FrameInfo fi;
        *given = poc || idr_pic_id || seed || matrix_coefficients;
        fi.ids.poc = poc ? *poc : 0;
        fi.ids.idr_pic_id = idr_pic_id;
        fi.seed = seed;
        fi.matrix_coefficients = matrix_coefficients;
        return fi;
    }

    py::object apply(const py::object& planes, std::optional<int> bit_depth, std::optional<std::string> chroma,
                     std::optional<int> poc, int idr_pic_id, std::optional<uint32_t> seed,
                     std::optional<int> matrix_coefficients, bool inplace) {
        NumpyPicture src = picture_from_planes(planes, bit_depth, chroma, inplace);
        const SessionOptions& o = session_.options();
        const int out_depth = o.flavour == FgcFlavour::kVfgs && o.vfgs_output_bit_depth ? o.vfgs_output_bit_depth
                                                                                         : src.view.bit_depth;
        if (inplace && out_depth != src.view.bit_depth)
            throw Error(ErrorCode::kInvalidArgument, "inplace: vfgs_output_bit_depth changes the bit depth");
        NumpyPicture dst = inplace ? src : new_picture_like(src.view, out_depth);
        bool given = false;
        FrameInfo fi = info_for(poc, idr_pic_id, seed, matrix_coefficients, &given);
        ApplyResult r;
        {
            py::gil_scoped_release release;
            std::lock_guard<std::mutex> lock(mutex_);
            if (feed_) {
                FrameInfo fed = feed_->feed(session_, fed_pictures_, fps_num_, fps_den_);
                if (given) {
                    fed.ids = fi.ids;
                    if (fi.seed) fed.seed = fi.seed;
                    if (fi.matrix_coefficients) fed.matrix_coefficients = fi.matrix_coefficients;
                }
                fi = fed;
                given = true;
            }
            r = session_.apply(src.view, dst.view, given ? &fi : nullptr);
            fed_pictures_++;
        }
        last_.grain_applied = r.grain_applied;
        last_.message = r.message;
        last_.parameters_refused = r.parameters_refused;
        return planes_list(dst);
    }

    void skip_picture(std::optional<int> poc, int idr_pic_id, int width, int height) {
        bool given = false;
        FrameInfo fi = info_for(poc, idr_pic_id, std::nullopt, std::nullopt, &given);
        std::lock_guard<std::mutex> lock(mutex_);
        if (feed_) {
            FrameInfo fed = feed_->feed(session_, fed_pictures_, fps_num_, fps_den_);
            if (given) fed.ids = fi.ids;
            fi = fed;
            given = true;
        }
        session_.skip_picture(width, height, given ? &fi : nullptr);
        fed_pictures_++;
    }

    py::dict last_result() const {
        py::dict d;
        d["grain_applied"] = last_.grain_applied;
        d["message"] = last_.message;
        d["parameters_refused"] = last_.parameters_refused;
        return d;
    }

private:
    std::mutex mutex_;
    Session session_;
    std::unique_ptr<session::ParameterFileFeed> feed_;
    int fps_num_ = 25, fps_den_ = 1;
    int fed_pictures_ = 0;
    ApplyResult last_;
};

SessionOptions session_options(const std::string& flavour, const std::string& persistence, const std::string& on_invalid,
                               int threads, int coded_width, int coded_height, int block_size, int single_line_blocks,
                               bool pattern_interpolation, std::optional<uint32_t> vfgs_seed, int vfgs_gain_percent,
                               int vfgs_output_bit_depth, int clip_to_restricted_range, bool reference_kernels) {
    SessionOptions o;
    o.flavour = cli::parse_flavour(flavour);
    if (persistence != "reference" && persistence != "semantic")
        throw Error(ErrorCode::kInvalidArgument, "persistence '" + persistence + "' is not known (allowed reference, semantic)");
    o.persistence = persistence == "semantic" ? FgcPersistence::kSemantic : FgcPersistence::kReference;
    if (on_invalid != "error" && on_invalid != "passthrough")
        throw Error(ErrorCode::kInvalidArgument, "on_invalid '" + on_invalid + "' is not known (allowed error, passthrough)");
    o.passthrough_invalid = on_invalid == "passthrough";
    o.threads = threads;
    o.coded_width = coded_width;
    o.coded_height = coded_height;
    o.block_size = block_size;
    o.single_line_blocks = single_line_blocks;
    o.pattern_interpolation = pattern_interpolation;
    o.vfgs_seed = vfgs_seed;
    o.vfgs_gain_percent = vfgs_gain_percent;
    o.vfgs_output_bit_depth = vfgs_output_bit_depth;
    o.clip_to_restricted_range = clip_to_restricted_range;
    o.reference_kernels = reference_kernels;
    return o;
}

}  // namespace

void register_session(py::module_& m) {
    using namespace pybind11::literals;
    py::class_<PySession>(m, "Session", R"doc(
One stream's film grain, whatever the model: the session every filmgrain entry point runs on.

Metadata goes in as it arrives (FGC SEI payloads or parameter dicts, AV1 frame-header grain,
AFGS1 T.35 payloads, or parameter files attached with attach_files) and every output picture
goes through apply(). The session keeps what a decoder would: SEIs waiting for their picture,
persistence and cancel, the AV1 reference slots, the AFGS1 stored sets.

Options (keywords): flavour ("rdd5", "vtm", "vfgs", "tr", "ffmpeg"), persistence ("reference",
"semantic"), on_invalid ("error": apply raises ValueError; "passthrough": the picture is
returned unchanged and last_result says why), threads (0 = all cores; the output is the same
for any count), coded_width / coded_height (vtm block size), block_size, single_line_blocks,
pattern_interpolation, vfgs_seed, vfgs_gain_percent, vfgs_output_bit_depth,
clip_to_restricted_range (-1 keeps the set's), reference_kernels (scalar reference stages).
)doc")
        .def(py::init([](const std::string& flavour, const std::string& persistence, const std::string& on_invalid,
                         int threads, int coded_width, int coded_height, int block_size, int single_line_blocks,
                         bool pattern_interpolation, std::optional<uint32_t> vfgs_seed, int vfgs_gain_percent,
                         int vfgs_output_bit_depth, int clip_to_restricted_range, bool reference_kernels) {
                 return std::make_unique<PySession>(session_options(
                     flavour, persistence, on_invalid, threads, coded_width, coded_height, block_size,
                     single_line_blocks, pattern_interpolation, vfgs_seed, vfgs_gain_percent, vfgs_output_bit_depth,
                     clip_to_restricted_range, reference_kernels));
             }),
             py::kw_only(), "flavour"_a = "rdd5", "persistence"_a = "reference", "on_invalid"_a = "error",
             "threads"_a = 0, "coded_width"_a = 0, "coded_height"_a = 0, "block_size"_a = 0,
             "single_line_blocks"_a = 0, "pattern_interpolation"_a = false, "vfgs_seed"_a = py::none(),
             "vfgs_gain_percent"_a = 100, "vfgs_output_bit_depth"_a = 0, "clip_to_restricted_range"_a = -1,
             "reference_kernels"_a = false)
        .def("push_fgc_sei", &PySession::push_fgc_sei, "payload"_a, "codec"_a = "hevc", py::kw_only(),
             "poc"_a = py::none(), "idr_pic_id"_a = 0,
             "An FGC SEI payload (payloadType 19 body) for the picture with this POC / idr_pic_id (poc None: the "
             "next picture applied). Raises ValueError naming the syntax element of a malformed payload.")
        .def("push_fgc_params", &PySession::push_fgc_params, "params"_a, "codec"_a = "hevc", py::kw_only(),
             "poc"_a = py::none(), "idr_pic_id"_a = 0,
             "An FGC SEI as a dict named after its syntax elements (filmgrain.params JSON form).")
        .def("push_av1_params", &PySession::push_av1_params, "params"_a, "refresh_frame_flags"_a = 0,
             "matrix_coefficients"_a = 2,
             "A frame header's film_grain_params() as a dict; update_grain = 0 is resolved from the reference "
             "slots, and the result is stored in the slots of refresh_frame_flags.")
        .def("show_existing_av1_frame", &PySession::show_existing_av1_frame, "frame_to_show_map_idx"_a)
        .def("push_afgs1", &PySession::push_afgs1, "payload"_a,
             "An AFGS1 ITU-T T.35 payload (with or without the B5 5890 01 header) for the next picture applied.")
        .def("attach_files", &PySession::attach_files, py::kw_only(), "params"_a = py::none(),
             "sei"_a = std::vector<std::string>{}, "afgs1"_a = std::vector<std::string>{}, "sei_codec"_a = py::none(),
             "matrix_coefficients"_a = -1, "fps_num"_a = 25, "fps_den"_a = 1,
             "Parameter files as `filmgrain apply` takes them (params: JSON / .tbl / payload file; sei or afgs1: "
             "one file for every picture, one per picture, or a %d pattern). Each later apply() first hands the "
             "session the metadata of its picture (counted from 0).")
        .def("apply", &PySession::apply, "planes"_a, py::kw_only(), "bit_depth"_a = py::none(), "chroma"_a = py::none(),
             "poc"_a = py::none(), "idr_pic_id"_a = 0, "seed"_a = py::none(), "matrix_coefficients"_a = py::none(),
             "inplace"_a = false,
             R"doc(Adds the grain in force to one picture in output order and returns its planes.

planes: a 2-D array (grey) or a list of Y, Cb, Cr arrays, uint8 (8-bit) or uint16 (bit_depth
9..16 required). The chroma format follows from the plane sizes (or chroma="420"/"422"/"444").
poc / idr_pic_id: the picture's ids (default: pictures counted from 0); seed: the picture's
seed instead (FGC pic_offset, AV1 grain_seed); inplace: write into the given arrays.
The GIL is released while the grain is synthesized.)doc")
        .def("skip_picture", &PySession::skip_picture, py::kw_only(), "poc"_a = py::none(), "idr_pic_id"_a = 0,
             "width"_a = 0, "height"_a = 0,
             "Follows the stream over one picture without synthesizing it (state moves on as apply() moves it).\n"
             "width / height: the picture's luma size, which the vfgs flavour needs (its random state steps once\n"
             "per 16x16 block); the other models ignore it.")
        .def("reset", &PySession::reset, "Forgets the stream (a seek or a new stream).")
        .def_property_readonly("last_result", &PySession::last_result,
                               "The last apply(): grain_applied, message (why no grain), parameters_refused.");
}

}  // namespace filmgrain::python
