// The CLI's commands for Python: run_command (any command line, in-process), stats on
// arrays, render of a numpy plane, and the parts of render / apply / analyze that
// python/filmgrain/distributed.py hands to Dask workers. Options are parsed by the CLI's
// own option definitions, so keyword arguments, checks and messages are the CLI's.
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "apply_job.hpp"
#include "bitstream/decode_restart.hpp"
#include "bitstream/stream_scan.hpp"
#include "command_line.hpp"
#include "core/float_plane.hpp"
#include "physical/cell_random.hpp"
#include "python/numpy_planes.hpp"
#include "python/python_module.hpp"
#include "render_job.hpp"
#include "stats/grain_statistics.hpp"
#include "stats_report.hpp"
#ifdef FILMGRAIN_HAVE_ANALYSIS
#include "analysis/observation_records.hpp"
#include "analysis_job.hpp"
#endif

namespace filmgrain::python {
namespace {

py::object json_to_python(const nlohmann::json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

FloatPlane float_plane_of(const py::array& a, int bit_depth, const char* what) {
    if (a.ndim() != 2) throw Error(ErrorCode::kInvalidArgument, std::string(what) + ": a plane has 2 dimensions");
    FloatPlane f(int(a.shape(1)), int(a.shape(0)));
    if (a.dtype().kind() == 'f') {
        const auto c = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
        std::copy(c.data(), c.data() + c.size(), f.v.begin());
        return f;
    }
    const std::optional<std::string> no_chroma;
    NumpyPicture pic = picture_from_planes(a, a.itemsize() == 1 ? std::optional<int>(8) : std::optional<int>(bit_depth),
                                           no_chroma, false);
    return float_plane_from(pic.view.planes[0], pic.view.bit_depth);
}

py::array float_array(const FloatPlane& f) {
    py::array_t<float> a({py::ssize_t(f.height), py::ssize_t(f.width)});
    std::copy(f.v.begin(), f.v.end(), a.mutable_data());
    return a;
}

py::list frame_planes(const FrameBuffer& fb) {
    FrameBuffer& f = const_cast<FrameBuffer&>(fb);
    FrameView v = f.view();
    NumpyPicture pic = new_picture_like(v, v.bit_depth);
    copy_frame(v, pic.view);
    return planes_list(pic);
}

}  // namespace

void register_video_files(py::module_& m) {
    using namespace pybind11::literals;
    py::class_<VideoInfo>(m, "VideoInfo", "Size, format and rate of a Y4M / raw YUV clip.")
        .def(py::init([](int width, int height, const std::string& pix_fmt, const std::string& fps, bool y4m) {
                 cli::RawVideoOptions r;
                 r.size = std::to_string(width) + "x" + std::to_string(height);
                 r.pix_fmt = pix_fmt;
                 r.fps = fps;
                 VideoInfo info = r.to_info();
                 info.y4m = y4m;
                 return info;
             }),
             "width"_a, "height"_a, "pix_fmt"_a = "yuv420p", "fps"_a = "25", "y4m"_a = true,
             "A clip's size, pix_fmt (yuv420p, yuv422p10le, gray, ...) and rate (\"25\", \"24000/1001\").")
        .def_readonly("width", &VideoInfo::width)
        .def_readonly("height", &VideoInfo::height)
        .def_property_readonly("pix_fmt", [](const VideoInfo& i) { return pix_fmt_name(i.format); })
        .def_property_readonly("bit_depth", [](const VideoInfo& i) { return i.format.bit_depth; })
        .def_readonly("fps_num", &VideoInfo::fps_num)
        .def_readonly("fps_den", &VideoInfo::fps_den)
        .def_readonly("y4m", &VideoInfo::y4m)
        .def_property_readonly("frame_bytes", [](const VideoInfo& i) { return FrameBuffer::frame_bytes(i.width, i.height, i.format); });

    py::class_<VideoReader>(m, "VideoReader", "Reads a Y4M or raw YUV clip picture by picture (planes as numpy arrays).")
        .def(py::init([](const std::string& path, const std::string& size, const std::string& pix_fmt,
                         const std::string& fps) {
                 cli::RawVideoOptions r;
                 r.size = size;
                 r.pix_fmt = pix_fmt;
                 r.fps = fps;
                 return std::make_unique<VideoReader>(path, size.empty() ? VideoInfo{} : r.to_info());
             }),
             "path"_a, py::kw_only(), "size"_a = "", "pix_fmt"_a = "yuv420p", "fps"_a = "25")
        .def_property_readonly("info", &VideoReader::info)
        .def("skip", &VideoReader::skip_frames, "count"_a, "Passes over pictures without reading them (seeks).")
        .def("read", [](VideoReader& r) -> py::object {
            FrameBuffer fb;
            bool ok;
            {
                py::gil_scoped_release release;
                ok = r.read(fb);
            }
            if (!ok) return py::none();
            return frame_planes(fb);
        }, "The next picture's planes, or None at the end.");

    py::class_<VideoWriter>(m, "VideoWriter",
                            "Writes a clip as `filmgrain` writes it; the file appears only at commit().")
        .def(py::init([](const std::string& path, const VideoInfo& info, bool y4m) {
                 return std::make_unique<VideoWriter>(path, info, y4m);
             }),
             "path"_a, "info"_a, "y4m"_a)
        .def("write", [](VideoWriter& w, const py::object& planes, std::optional<int> bit_depth) {
            NumpyPicture pic = picture_from_planes(planes, bit_depth, std::nullopt, false);
            py::gil_scoped_release release;
            w.write(pic.view);
        }, "planes"_a, py::kw_only(), "bit_depth"_a = py::none())
        .def("write_raw", [](VideoWriter& w, const py::bytes& frame, const VideoInfo& info) {
            const std::string b = frame;
            FrameBuffer fb = FrameBuffer::uninitialized(info.width, info.height, info.format);
            if (b.size() != fb.byte_size())
                throw Error(ErrorCode::kInvalidArgument, "a raw frame of " + std::to_string(b.size()) + " bytes, expected " +
                                                             std::to_string(fb.byte_size()));
            std::copy(b.begin(), b.end(), fb.bytes());
            w.write(fb);
        }, "frame"_a, "info"_a)
        .def("commit", &VideoWriter::commit);
}

void register_commands(py::module_& m) {
    using namespace pybind11::literals;
    m.def("run_command", [](const std::vector<std::string>& args) {
        py::gil_scoped_release release;
        cli::run_command_or_throw(args);
    }, "args"_a, "Runs a `filmgrain` command line in-process (without the program name); raises on failure.");

    m.def("stream_picture_count", [](const std::string& path) {
        py::gil_scoped_release release;
        const bitstream::StreamScan scan = bitstream::scan_stream_file(path, std::nullopt);
        // an access unit (AV1: temporal unit) outputs one picture unless a decoder drops it
        std::size_t n = 0;
        for (const bitstream::AccessUnit& u : scan.units) n += u.output && u.pictures > 0;
        return n;
    }, "path"_a, "Pictures in output order of an H.264 / H.265 / H.266 / AV1 elementary stream (a metadata scan).");

    m.def("stream_restart_points", [](const std::string& path) {
        py::gil_scoped_release release;
        std::vector<int64_t> points;
        for (const bitstream::DecodeRestart& r : bitstream::decode_restart_points(bitstream::scan_stream_file(path, std::nullopt)))
            points.push_back(r.output_before);
        return points;
    }, "path"_a, "Output pictures `filmgrain decode --first-frame` can start decoding at (not at the stream's start), "
                 "ascending: its random access points that give what decoding from the start gives.");

    m.def("stats_files", [](const std::vector<std::string>& args) {
        const cli::StatsOptions o = cli::parse_subcommand_arguments<cli::StatsOptions>("stats", cli::add_stats_options, args);
        nlohmann::json j;
        {
            py::gil_scoped_release release;
            j = cli::grain_statistics_report(o);
        }
        return json_to_python(j);
    }, "args"_a);

    m.def("stats_arrays", [](const py::array& clean, const py::array& grainy, const std::vector<std::string>& args,
                             int bit_depth) {
        cli::StatsOptions o = cli::parse_subcommand_arguments<cli::StatsOptions>("stats", cli::add_stats_options, args);
        const FloatPlane c = float_plane_of(clean, bit_depth, "clean"), g = float_plane_of(grainy, bit_depth, "grainy");
        if (c.width != g.width || c.height != g.height)
            throw Error(ErrorCode::kInvalidArgument, "grainy is " + std::to_string(g.width) + "x" + std::to_string(g.height) +
                                                         ", clean " + std::to_string(c.width) + "x" + std::to_string(c.height));
        nlohmann::json j;
        {
            py::gil_scoped_release release;
            j = cli::statistics_json(c, stats::grain_of(c, g), o);
        }
        return json_to_python(j);
    }, "clean"_a, "grainy"_a, "args"_a, "bit_depth"_a);

    m.def("render_array", [](const py::array& plane, const std::vector<std::string>& args, int bit_depth, int frame, int plane_index) {
        // the render options of a still, applied to one grey plane with the seed of (frame, plane)
        const cli::RenderOptions o = cli::parse_subcommand_arguments<cli::RenderOptions>("render", cli::add_render_options, args);
        const FloatPlane u = float_plane_of(plane, bit_depth, "plane");
        const physical::BooleanModelParams p = cli::render_model_params(o);
        physical::OutputRegion r;
        r.w = physical::zoomed_size(u.width, p.zoom);
        r.h = physical::zoomed_size(u.height, p.zoom);
        FloatPlane out;
        {
            py::gil_scoped_release release;
            physical::render_boolean_model(u, p, r, physical::hash_coordinates(frame, plane_index, p.seed), out);
        }
        return float_array(out);
    }, "plane"_a, "args"_a, "bit_depth"_a, "frame"_a, "plane_index"_a);

    py::class_<cli::RenderJob>(m, "RenderJob", "`filmgrain render` cut into frames and tiles (distributed render).")
        .def(py::init([](const std::vector<std::string>& args) {
            return std::make_unique<cli::RenderJob>(cli::parse_subcommand_arguments<cli::RenderOptions>("render", cli::add_render_options, args));
        }), "args"_a)
        .def_property_readonly("video", &cli::RenderJob::video)
        .def_property_readonly("output_width", &cli::RenderJob::output_width)
        .def_property_readonly("output_height", &cli::RenderJob::output_height)
        .def_property_readonly("output_info", &cli::RenderJob::output_info)
        .def_property_readonly("output_y4m", &cli::RenderJob::output_y4m)
        .def_property_readonly("frame_count", &cli::RenderJob::frame_count)
        .def_property_readonly("channels", [](const cli::RenderJob& j) { return j.video() ? 0 : int(j.still().channels.size()); })
        .def_property_readonly("tile_alignment", [](const cli::RenderJob& j) {
            return py::make_tuple(j.tile_alignment_x(), j.tile_alignment_y());
        })
        .def("render_video_tile", [](const cli::RenderJob& j, int k, int x, int y, int w, int h) {
            FrameBuffer out;
            {
                py::gil_scoped_release release;
                VideoReader reader(j.options().input, j.options().raw.to_info());
                if (!reader.skip_frames(k))
                    throw Error(ErrorCode::kInvalidArgument, "frame " + std::to_string(k) + " is beyond the input's end");
                FrameBuffer in;
                if (!reader.read(in))
                    throw Error(ErrorCode::kInvalidArgument, "frame " + std::to_string(k) + " is beyond the input's end");
                cli::RenderTotals t;
                j.render_video_tile(in, k, physical::OutputRegion{x, y, w, h}, out, t);
            }
            return frame_planes(out);
        }, "frame"_a, "x"_a, "y"_a, "w"_a, "h"_a, "Renders a tile of frame k: its planes (the output's sample type).")
        .def("render_still_tile", [](const cli::RenderJob& j, int c, int x, int y, int w, int h) {
            FloatPlane out;
            {
                py::gil_scoped_release release;
                cli::RenderTotals t;
                j.render_still_tile(c, physical::OutputRegion{x, y, w, h}, out, t);
            }
            return float_array(out);
        }, "channel"_a, "x"_a, "y"_a, "w"_a, "h"_a)
        .def("write_still", [](const cli::RenderJob& j, const std::string& path, const std::vector<py::array>& channels) {
            cli::StillImage img = j.still();
            if (channels.size() != img.channels.size())
                throw Error(ErrorCode::kInvalidArgument, std::to_string(channels.size()) + " channels for a still of " +
                                                             std::to_string(img.channels.size()));
            for (std::size_t c = 0; c < channels.size(); c++) img.channels[c] = float_plane_of(channels[c], 8, "channel");
            py::gil_scoped_release release;
            cli::write_still_image(path, img);
        }, "path"_a, "channels"_a, "Writes the joined channels as `filmgrain render` writes the still.");

    py::class_<cli::ApplyJob>(m, "ApplyJob", "`filmgrain apply` cut into ranges of pictures (distributed apply).")
        .def(py::init([](const std::vector<std::string>& args) {
            return std::make_unique<cli::ApplyJob>(cli::parse_subcommand_arguments<cli::ApplyOptions>("apply", cli::add_apply_options, args));
        }), "args"_a)
        .def_property_readonly("output_info", &cli::ApplyJob::output_info)
        .def_property_readonly("output_y4m", &cli::ApplyJob::output_y4m)
        .def_property_readonly("frame_count", &cli::ApplyJob::frame_count)
        .def("run_range", [](cli::ApplyJob& j, int from, int to, const std::string& part) {
            py::gil_scoped_release release;
            return j.run_range(from, to, part);
        }, "first"_a, "end"_a, "part"_a, "Pictures [first, end) as raw frames into `part`; returns how many.");

#ifdef FILMGRAIN_HAVE_ANALYSIS
    py::class_<cli::AnalysisJob>(m, "AnalysisJob", "`filmgrain analyze` cut into ranges of pictures (distributed analyze).")
        .def(py::init([](const std::vector<std::string>& args) {
            return std::make_unique<cli::AnalysisJob>(cli::parse_subcommand_arguments<cli::AnalyzeOptions>("analyze", cli::add_analyze_options, args));
        }), "args"_a)
        .def_property_readonly("frame_count", &cli::AnalysisJob::frame_count)
        .def_property_readonly("frame_step", &cli::AnalysisJob::frame_step)
        .def_property_readonly("temporal_radius", &cli::AnalysisJob::temporal_radius)
        .def("observe_range", [](const cli::AnalysisJob& j, int from, int to) {
            std::vector<std::vector<uint8_t>> records;
            {
                py::gil_scoped_release release;
                for (const auto& p : j.observe_range(from, to)) records.push_back(analysis::serialize_picture_observations(p));
            }
            py::list out;
            for (const auto& r : records) out.append(py::bytes(reinterpret_cast<const char*>(r.data()), r.size()));
            return out;
        }, "first"_a, "end"_a, "The observations of the analysed pictures in [first, end), one record each.")
        .def("fit_and_write", [](const cli::AnalysisJob& j, const std::vector<py::bytes>& records, int frames) {
            std::vector<analysis::PictureObservations> pictures;
            for (const py::bytes& b : records) {
                const std::string s = b;
                pictures.push_back(analysis::deserialize_picture_observations(reinterpret_cast<const uint8_t*>(s.data()), s.size()));
            }
            for (std::size_t i = 1; i < pictures.size(); i++)
                if (pictures[i].index <= pictures[i - 1].index)
                    throw Error(ErrorCode::kInvalidArgument, "observation records out of picture order (" +
                                                                 std::to_string(pictures[i - 1].index) + " then " +
                                                                 std::to_string(pictures[i].index) + ")");
            py::gil_scoped_release release;
            j.write_outputs_from(pictures, frames);
        }, "records"_a, "frames"_a, "Fits the records (in picture order) once and writes the outputs as the CLI does.");
    m.attr("have_analysis") = true;
#else
    m.attr("have_analysis") = false;
#endif
}

}  // namespace filmgrain::python
