// `filmgrain apply`: add grain to a raw YUV or Y4M file from parameters (JSON, SEI payloads).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "fgc/fgc_synthesizer.hpp"
#include "filmgrain/error.hpp"
#include "io/xz_file.hpp"
#include "metadata/fgc_sei.hpp"
#include "metadata/params_file.hpp"

namespace filmgrain::cli {
namespace {

struct ApplyOptions {
    std::string input, output, params;
    std::vector<std::string> sei;
    std::string sei_codec = "hevc";
    std::string flavour = "rdd5";
    std::string on_invalid = "error";
    std::string persistence = "reference";
    int block_size = 0;
    std::string coded_size;
    int threads = 0;
    bool quiet = false;
    RawVideoOptions raw;
};

// Where each picture's FGC SEI comes from.
class FgcSource {
public:
    virtual ~FgcSource() = default;
    // The SEI that arrives with picture k (if any) and its ids.
    virtual std::optional<FgcParams> sei_for(int k, FgcPictureIds& ids) = 0;
};

class ParamsFileSource : public FgcSource {
public:
    explicit ParamsFileSource(ParamsFile f) : f_(std::move(f)) {}
    std::optional<FgcParams> sei_for(int k, FgcPictureIds& ids) override {
        ids = FgcPictureIds{k, 0};
        if (!f_.per_frame) return f_.frames[0].fgc;  // one object: every picture
        if (std::size_t(k) >= f_.frames.size()) return std::nullopt;
        const FrameParams& fr = f_.frames[k];
        if (fr.poc) ids.poc = *fr.poc;
        if (fr.idr_pic_id) ids.idr_pic_id = *fr.idr_pic_id;
        if (fr.pic_offset) ids = FgcPictureIds{*fr.pic_offset, 0};
        return fr.fgc;
    }

private:
    ParamsFile f_;
};

class SeiFileSource : public FgcSource {
public:
    SeiFileSource(std::vector<std::string> files, FgcCodec codec) : files_(std::move(files)), codec_(codec) {
        for (const auto& f : files_)
            if (f.find('%') == std::string::npos) fixed_.push_back(parse_fgc_sei_payload(read_whole_file(f), codec_));
    }
    std::optional<FgcParams> sei_for(int k, FgcPictureIds& ids) override {
        ids = FgcPictureIds{k, 0};
        if (files_.size() == 1 && files_[0].find('%') != std::string::npos) {
            char name[4096];
            std::snprintf(name, sizeof name, files_[0].c_str(), k);
            if (!std::filesystem::exists(name)) return std::nullopt;
            return parse_fgc_sei_payload(read_whole_file(name), codec_);
        }
        if (fixed_.size() == 1) return fixed_[0];  // one payload: every picture
        if (std::size_t(k) < fixed_.size()) return fixed_[k];
        return std::nullopt;
    }

private:
    std::vector<std::string> files_;
    FgcCodec codec_;
    std::vector<FgcParams> fixed_;
};

int run_apply(const ApplyOptions& o) {
    const FgcFlavour flavour = parse_flavour(o.flavour);
    if (o.on_invalid != "error" && o.on_invalid != "passthrough")
        throw Error(ErrorCode::kInvalidArgument, "--on-invalid '" + o.on_invalid + "' is not known (allowed error, passthrough)");
    if (o.persistence != "reference" && o.persistence != "semantic")
        throw Error(ErrorCode::kInvalidArgument,
                    "--persistence '" + o.persistence + "' is not known (allowed reference, semantic)");
    if (o.params.empty() == o.sei.empty())
        throw Error(ErrorCode::kInvalidArgument, "give exactly one of --params FILE or --sei FILE");
    const FgcCodec codec = parse_fgc_codec(o.sei_codec);

    std::unique_ptr<FgcSource> source;
    if (!o.params.empty()) {
        ParamsFile pf = load_params_file(o.params);
        if (!pf.has_fgc() && pf.has_av1())
            throw Error(ErrorCode::kUnsupported, "AV1 film grain parameters are not handled by this build yet");
        source = std::make_unique<ParamsFileSource>(std::move(pf));
    } else {
        source = std::make_unique<SeiFileSource>(o.sei, codec);
    }
    if (flavour == FgcFlavour::kVfgs) throw Error(ErrorCode::kUnsupported, "--flavour vfgs is not available in this build yet");

    FgcOptions fo;
    fo.flavour = flavour;
    fo.persistence = o.persistence == "semantic" ? FgcPersistence::kSemantic : FgcPersistence::kReference;
    fo.block_size = o.block_size;
    if (!o.coded_size.empty()) {
        RawVideoOptions cs;
        cs.size = o.coded_size;
        VideoInfo ci = cs.to_info();
        fo.coded_width = ci.width;
        fo.coded_height = ci.height;
    }
    fo.passthrough_invalid = o.on_invalid == "passthrough";
    FgcSynthesizer synth(fo);

    VideoReader reader(o.input, o.raw.to_info());
    const bool y4m_out = o.output != "-" ? has_y4m_extension(o.output) : reader.info().y4m;
    VideoWriter writer(o.output, reader.info(), y4m_out);
    FrameBuffer in, out;
    int k = 0;
    while (reader.read(in)) {
        if (out.byte_size() != in.byte_size()) out = FrameBuffer(in.width(), in.height(), in.format());
        FgcPictureIds ids;
        if (auto sei = source->sei_for(k, ids)) synth.receive_sei(*sei, codec);
        FgcFrameResult r = synth.apply(in.view(), out.view(), ids);
        if (!r.message.empty() && !o.quiet) std::fprintf(stderr, "filmgrain: frame %d: %s\n", k, r.message.c_str());
        writer.write(out);
        k++;
    }
    if (k == 0) throw Error(ErrorCode::kIo, "input '" + o.input + "' holds no frame");
    writer.commit();
    if (!o.quiet && o.output != "-")
        std::fprintf(stderr, "filmgrain: %d frame(s) written to %s (flavour %s)\n", k, o.output.c_str(),
                     flavour_name(flavour).c_str());
    return 0;
}

}  // namespace

void register_apply(CLI::App& app) {
    auto o = std::make_shared<ApplyOptions>();
    CLI::App* sub = app.add_subcommand("apply", "add film grain to a raw YUV or Y4M file");
    sub->add_option("--input,-i", o->input, "input file (raw planar YUV or Y4M), - for stdin")->required();
    sub->add_option("--output,-o", o->output, "output file (.y4m writes Y4M), - for stdout")->required();
    sub->add_option("--params,-p", o->params, "parameter file: JSON (FGC SEI syntax elements or per-frame list)");
    sub->add_option("--sei", o->sei,
                    "raw FGC SEI payload(s) (payloadType 19 body); one file for every picture, several for "
                    "pictures 0,1,..., or a printf pattern such as frame%d.fgc.bin (missing = no SEI)");
    sub->add_option("--sei-codec", o->sei_codec, "SEI syntax variant: avc, hevc or vvc")->capture_default_str();
    sub->add_option("--flavour", o->flavour, "rdd5 (SMPTE RDD 5 / FFmpeg), vtm (HM/VTM reference) or vfgs")
        ->capture_default_str();
    sub->add_option("--on-invalid", o->on_invalid,
                    "invalid parameter set: error (exit non-zero) or passthrough (picture unchanged, as the references)")
        ->capture_default_str();
    sub->add_option("--persistence", o->persistence,
                    "pictures without an SEI: reference (HM: reuse the last SEI) or semantic (persistence_flag)")
        ->capture_default_str();
    sub->add_option("--block-size", o->block_size, "force the adaptation block size 8, 16 or 32 (0: flavour default)");
    sub->add_option("--coded-size", o->coded_size,
                    "vtm: the stream's coded picture size WxH (SPS), which picks HM's block size "
                    "(default: the picture size rounded up to a multiple of 16)");
    sub->add_option("--threads", o->threads, "worker threads (0: all cores)");
    sub->add_flag("--quiet,-q", o->quiet, "no messages on stderr except errors");
    o->raw.add_to(sub);
    sub->callback([o]() {
        int rc = run_apply(*o);
        if (rc) throw CLI::RuntimeError(rc);
    });
}

}  // namespace filmgrain::cli
