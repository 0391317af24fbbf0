// `filmgrain analyze`: estimate FGC SEI or AV1 grain parameters from grainy video (TR 23002-9
// clause 8), optionally with its denoised version; writes parameters usable as
// `apply --params`, a libaom grain table, an FGC SEI payload and an HTML report.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "cli_common.hpp"
#include "filmgrain/error.hpp"
#include "grain_outputs.hpp"
#include "analysis_job.hpp"

#ifdef FILMGRAIN_HAVE_ANALYSIS
#include <opencv2/core.hpp>

#include "analysis/analysis_report.hpp"
#include "analysis/grain_analyzer.hpp"
#include "analysis/plane_image.hpp"
#include "core/field_names.hpp"
#include "filmgrain/session.hpp"
#include "metadata/afgs1.hpp"
#include "metadata/fgc_sei.hpp"
#endif

namespace filmgrain::cli {

#ifdef FILMGRAIN_HAVE_ANALYSIS
namespace {

std::string percent(double x, int decimals = 1) {
    char b[40];
    std::snprintf(b, sizeof b, "%.*f%%", decimals, 100 * x);
    return b;
}

std::string list_percent(const std::vector<double>& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); i++) s += (i ? ", " : "") + percent(v[i]);
    return s;
}

FrameBuffer picture_from_planes(const std::array<cv::Mat, 3>& planes, PixelFormat fmt, int w, int h) {
    FrameBuffer fb(w, h, fmt);
    FrameView v = fb.view();
    for (int p = 0; p < v.plane_count(); p++) analysis::float_to_plane(planes[p], v, p);
    return fb;
}

cv::Mat centre_crop(const cv::Mat& m, int size) {
    const int w = std::min(size, m.cols), h = std::min(size, m.rows);
    return m(cv::Rect((m.cols - w) / 2, (m.rows - h) / 2, w, h)).clone();
}

void check_analyze_options(const AnalyzeOptions& o) {
    if (o.model != "fgc" && o.model != "av1")
        throw Error(ErrorCode::kInvalidArgument, "--model '" + o.model + "' is not known (allowed fgc, av1)");
    const bool fgc = o.model == "fgc";
    if (fgc && !o.table.empty()) throw Error(ErrorCode::kInvalidArgument, "--table belongs to --model av1");
    if (fgc && !o.afgs1.empty()) throw Error(ErrorCode::kInvalidArgument, "--afgs1 belongs to --model av1");
    if (!fgc && !o.sei.empty()) throw Error(ErrorCode::kInvalidArgument, "--sei belongs to --model fgc");
    const FgcFlavour flavour = parse_flavour(o.flavour);
    if (flavour == FgcFlavour::kVfgs)
        throw Error(ErrorCode::kInvalidArgument, "--flavour vfgs is not supported by analyze (allowed rdd5, vtm)");
    parse_fgc_codec(o.sei_codec);
    if (o.max_frames < 1) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("--max-frames", o.max_frames, 1, 1 << 30));
    if (o.frame_step < 0) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("--frame-step", o.frame_step, 0, 1 << 30));
    if (!(o.accuracy >= 0 && o.accuracy < 1))
        throw Error(ErrorCode::kInvalidArgument, "--accuracy " + std::to_string(o.accuracy) +
                                                     " is out of range (allowed 0..1, 1 exclusive; 0 = the model's default)");
    if (!(o.max_error > 0 && o.max_error <= 1))
        throw Error(ErrorCode::kInvalidArgument, "--max-error " + std::to_string(o.max_error) + " is out of range (allowed 0..1, 0 exclusive)");
    if (o.max_lag < 0 || o.max_lag > 3) throw Error(ErrorCode::kInvalidArgument, out_of_range_message("--max-lag", o.max_lag, 0, 3));

}

analysis::AnalysisOptions analysis_options_for(const AnalyzeOptions& o, long long total) {
    analysis::AnalysisOptions ao;
    ao.model = o.model == "fgc" ? analysis::GrainModel::kFgc : analysis::GrainModel::kAv1;
    ao.flavour = parse_flavour(o.flavour);
    // A subset of the pictures: grain statistics are stationary over a shot, and the
    // observations of ~32 pictures already pool thousands of blocks.
    ao.frame_step = o.frame_step > 0 ? o.frame_step : total > 0 ? int(std::max<long long>(1, (total + o.max_frames - 1) / o.max_frames)) : 8;
    ao.temporal_radius = o.temporal_radius;
    ao.spatial_only = o.spatial;
    ao.accuracy = o.accuracy;
    ao.max_ar_lag = o.max_lag;
    return ao;
}

}  // namespace

AnalysisJob::AnalysisJob(const AnalyzeOptions& options) : o_(options) {
    check_analyze_options(o_);
    // kept for run(): standard input can be opened once
    reader_ = std::make_unique<VideoReader>(o_.input, o_.raw.to_info());
    info_ = reader_->info();
    total_ = frame_count_from_size(o_.input, info_);
    ao_ = analysis_options_for(o_, total_);
}

std::unique_ptr<analysis::GrainAnalyzer> AnalysisJob::analyse_range(int from, int to) const {
    if (from < 0 || to < from)
        throw Error(ErrorCode::kInvalidArgument, "picture range [" + std::to_string(from) + ", " + std::to_string(to) +
                                                     ") is not a range of pictures");
    analysis::AnalysisOptions ao = ao_;
    const int radius = o_.denoised.empty() && !o_.spatial ? o_.temporal_radius : 0;
    ao.first_index = std::max(0, from - radius);
    ao.analyse_from = from;
    ao.analyse_to = to;
    ao.keep_picture_observations = true;
    VideoReader reader(o_.input, o_.raw.to_info());
    std::unique_ptr<VideoReader> dreader;
    if (!o_.denoised.empty()) dreader = std::make_unique<VideoReader>(o_.denoised, o_.raw.to_info());
    if (!reader.skip_frames(ao.first_index) || (dreader && !dreader->skip_frames(ao.first_index)))
        return nullptr;
    auto analyzer = std::make_unique<analysis::GrainAnalyzer>(ao, info_.format, info_.width, info_.height);
    FrameBuffer in, den;
    for (int k = ao.first_index; k < to + radius && reader.read(in); k++) {
        const FrameBuffer* dptr = nullptr;
        if (dreader) {
            if (!dreader->read(den))
                throw Error(ErrorCode::kIo, "--denoised '" + o_.denoised + "' ends at frame " + std::to_string(k) +
                                                " before the input");
            dptr = &den;
        }
        analyzer->add_frame(in, dptr);
    }
    analyzer->finish();
    return analyzer;
}

std::vector<analysis::PictureObservations> AnalysisJob::observe_range(int from, int to) const {
    const auto analyzer = analyse_range(from, to);
    return analyzer ? analyzer->picture_observations() : std::vector<analysis::PictureObservations>{};
}

int AnalysisJob::run() {
    const AnalyzeOptions& o = o_;
    const analysis::AnalysisOptions& ao = ao_;
    const long long total = total_;
    if (!reader_) reader_ = std::make_unique<VideoReader>(o.input, o.raw.to_info());
    VideoReader& reader = *reader_;
    std::unique_ptr<VideoReader> dreader;
    if (!o.denoised.empty()) dreader = std::make_unique<VideoReader>(o.denoised, o.raw.to_info());
    std::unique_ptr<analysis::GrainAnalyzer> analyzer;
    FrameBuffer in, den;
    int k = 0;
    while (reader.read(in)) {
        if (!analyzer) analyzer = std::make_unique<analysis::GrainAnalyzer>(ao, in.format(), in.width(), in.height());
        const FrameBuffer* dptr = nullptr;
        if (dreader) {
            if (!dreader->read(den))
                throw Error(ErrorCode::kIo, "--denoised '" + o.denoised + "' ends at frame " + std::to_string(k) +
                                                " before the input");
            dptr = &den;
        }
        analyzer->add_frame(in, dptr);
        k++;
        if (!o.quiet && k % 25 == 0) {
            if (total > 0)
                std::fprintf(stderr, "\rfilmgrain analyze: frame %d of %lld, %d analysed", k, total, analyzer->frames_analysed());
            else
                std::fprintf(stderr, "\rfilmgrain analyze: frame %d, %d analysed", k, analyzer->frames_analysed());
            std::fflush(stderr);
        }
    }
    if (k == 0) throw Error(ErrorCode::kIo, "input '" + o.input + "' holds no frame");
    analyzer->finish();
    if (!o.quiet && k >= 25) std::fprintf(stderr, "\n");
    write_outputs(*analyzer, k);
    return 0;
}

void AnalysisJob::write_outputs_from(const std::vector<analysis::PictureObservations>& pictures, int frames) const {
    if (frames <= 0) throw Error(ErrorCode::kIo, "input '" + o_.input + "' holds no frame");
    analysis::GrainAnalyzer analyzer(ao_, info_.format, info_.width, info_.height);
    for (const auto& p : pictures) analyzer.merge_picture(p);
    if (o_.report.empty() || pictures.empty()) return write_outputs(analyzer, frames);
    // The report's picture is the one the one-pass analyser keeps (GrainAnalyzer::add_frame):
    // the first analysed picture with a full set of neighbours before it, else the first.
    // Analysed again here on its own, with the same neighbours, it is the same picture.
    int sample = pictures.front().index;
    for (const auto& p : pictures)
        if (p.index >= 2 * ao_.temporal_radius) {
            sample = p.index;
            break;
        }
    const auto one = analyse_range(sample, sample + 1);
    if (!one || one->sample_picture().index != sample)
        throw Error(ErrorCode::kIo, "input '" + o_.input + "': picture " + std::to_string(sample) +
                                        " of the report could not be read again");
    write_outputs(analyzer, frames, &one->sample_picture());
}

void AnalysisJob::write_outputs(const analysis::GrainAnalyzer& analyzer_ref, int k,
                                const analysis::AnalysedPicture* sample_override) const {
    const AnalyzeOptions& o = o_;
    const VideoInfo& info = info_;
    const analysis::AnalysisOptions& ao = ao_;
    const analysis::GrainAnalyzer* analyzer = &analyzer_ref;
    const bool fgc = o.model == "fgc";
    const FgcFlavour flavour = parse_flavour(o.flavour);
    const FgcCodec codec = parse_fgc_codec(o.sei_codec);

    const PixelFormat fmt = info.format;
    std::string params_text;
    FgcParams fgc_params;
    std::vector<Av1FilmGrainParams> av1_frames;
    analysis::ReportInput rep;
    rep.bit_depth = fmt.bit_depth;
    const int nplanes = num_planes(fmt.chroma);
    auto pct = [&](double x) { return percent(x); };
    // The accuracy check: a component whose description misses the measured level curve by
    // more than --max-error (a model that cannot follow the grain, or observations too few
    // or too disturbed to trust) is refused (nothing written) unless --force, and named
    // either way. --accuracy is the target the fit aims for with as few points as it can;
    // real grain often cannot reach it where the model's form does not fit (chroma grain
    // that is no function of the chroma value alone), and that is no reason to refuse.
    std::vector<std::string> inaccurate;
    auto check_accuracy = [&](int c, bool present, double error, int band) {
        if (!present || error <= o.max_error) return std::string();
        std::ostringstream m;
        m << plane_name(c) << ": the fitted levels miss the measured grain level by " << pct(error);
        if (band >= 0) m << " in intensities " << band << ".." << band + analysis::kErrorBandWidth - 1;
        m << " (allowed at most " << pct(o.max_error) << ", --max-error)";
        inaccurate.push_back(m.str());
        return std::string(o.force ? "written despite failing its accuracy check (--force)"
                                   : "fails its accuracy check");
    };
    if (fgc) {
        const analysis::FgcEstimate e = analyzer->estimate_fgc();
        fgc_params = e.params;
        params_text = fgc_params_json_text(fgc_params);
        for (int c = 0; c < nplanes; c++) {
            const auto& r = e.components[c];
            analysis::ReportPlane rp;
            rp.name = plane_name(c);
            rp.present = fgc_params.comp[c].comp_model_present_flag && !fgc_params.film_grain_characteristics_cancel_flag;
            rp.curve = r.curve;
            rp.observations = analyzer->observations()[c].blocks;
            rp.intervals = r.intervals;
            rp.power = analysis::mean_power(analyzer->observations()[c], 0, 255);
            std::ostringstream s;
            if (r.present) {
                s << r.chosen_order << " interval(s), worst band error " << pct(r.error) << " (by count: "
                  << list_percent(r.error_by_order) << "); " << r.cutoff_pairs << " cut-off pair(s), signalled cut-offs";
                for (const auto& pr : r.cutoffs) s << " (" << pr.first << "," << pr.second << ")";
                char corr[200];
                std::snprintf(corr, sizeof corr,
                              " (observed correlation at lags 1, 2: horizontal %.3f %.3f, vertical %.3f %.3f, diagonal %.3f %.3f;"
                              " model mismatch %.3f)",
                              r.pooled.observed_x[1], r.pooled.observed_x[2], r.pooled.observed_y[1], r.pooled.observed_y[2],
                              r.pooled.observed_diagonal[0], r.pooled.observed_diagonal[1], r.pooled.mismatch);
                s << corr;
                s << "; log2_scale_factor " << fgc_params.log2_scale_factor;
            }
            if (!r.note.empty()) s << (r.present ? "; " : "") << r.note;
            if (const std::string a = check_accuracy(c, rp.present, r.error, r.worst_band); !a.empty()) s << "; " << a;
            s << "; " << r.curve.observations << " block observations, " << r.curve.outliers << " outliers removed";
            rp.summary = s.str();
            rep.planes.push_back(rp);
        }
    } else {
        const analysis::Av1Estimate e = analyzer->estimate_av1();
        av1_frames = av1_per_frame(e.params, k);
        const Av1ColorInfo color = av1_color_of(fmt);
        params_text = av1_params_json_text(av1_frames, color);
        for (int c = 0; c < nplanes; c++) {
            const auto& r = e.components[c];
            analysis::ReportPlane rp;
            rp.name = plane_name(c);
            rp.present = r.present && e.params.apply_grain;
            rp.curve = r.curve;
            // chroma curves and points are over the scaling index, which may mix in the luma
            rp.observations = analysis::blocks_by_chroma_index(analyzer->observations()[c].blocks, r.luma_quarters);
            rp.points = r.points;
            rp.power = analysis::mean_power(analyzer->observations()[c], 0, 255);
            std::ostringstream s;
            if (r.present) {
                s << r.points.size() << " scaling point(s), worst band error " << pct(r.error) << "; AR lag " << e.chosen_lag;
                if (c > 0 && !r.spread_by_luma_quarters.empty()) {
                    s << "; scaling index " << (4 - r.luma_quarters) * 25 << " % chroma + " << r.luma_quarters * 25
                      << " % luma (level spread around the curve for luma 0/25/50/75/100 %:";
                    char v[32];
                    for (double x : r.spread_by_luma_quarters) s << (std::snprintf(v, sizeof v, " %.3f", x), v);
                    s << ")";
                }
                if (!r.residual_by_lag.empty())
                    s << " (normalized residual by lag: " << list_percent(r.residual_by_lag)
                      << "; spectrum deviation from the longest lag: " << list_percent(r.spectrum_error_by_lag)
                      << ", accepted " << percent(r.lag_tolerance) << ")";
                s << "; scaling_shift " << e.params.grain_scaling_minus_8 + 8 << ", ar_coeff_shift "
                  << e.params.ar_coeff_shift_minus_6 + 6;
                if (c == 0)
                    s << "; clip_to_restricted_range " << e.params.clip_to_restricted_range << " ("
                      << (e.clipped_to_legal_range ? "no sample outside the studio range, " : "samples outside the studio range or none on its bounds, ")
                      << percent(e.on_legal_bound, 3) << " on its bounds)";
            }
            if (!r.note.empty()) s << (r.present ? "; " : "") << r.note;
            if (const std::string a = check_accuracy(c, rp.present, r.error, r.worst_band); !a.empty()) s << "; " << a;
            s << "; " << r.curve.observations << " block observations, " << r.curve.outliers << " outliers removed";
            rp.summary = s.str();
            rep.planes.push_back(rp);
        }
    }
    if (!inaccurate.empty() && !o.force) {
        std::string m;
        for (const auto& i : inaccurate) m += (m.empty() ? "" : "; ") + i;
        throw Error(ErrorCode::kInvalidArgument, m + "; nothing written: analyse more (or flatter) pictures, raise --max-error, "
                                                     "or add --force to write the set anyway");
    }

    if (!o.report.empty()) {
        const std::filesystem::path rp(o.report);
        if (rp.has_parent_path()) std::filesystem::create_directories(rp.parent_path());
        const auto& sample = sample_override ? *sample_override : analyzer->sample_picture();
        FrameBuffer den_fb = picture_from_planes(sample.denoised, fmt, info.width, info.height);
        FrameBuffer resynth = den_fb;
        // the round trip: the estimated set re-synthesized on the denoised picture
        SessionOptions so;
        so.flavour = flavour;
        Session session(so);
        FrameInfo fi;
        if (fgc) {
            session.receive_fgc_params(fgc_params, codec);
            fi.ids = FgcPictureIds{sample.index, 0};
        } else {
            Av1FilmGrainParams p = av1_frames.at(std::size_t(sample.index));
            p.update_grain = 1;
            session.receive_av1_params(p, 0, 2);
        }
        session.apply(den_fb.view(), resynth.view(), &fi);
        const int crop = 256;
        rep.source = centre_crop(sample.source[0], crop);
        rep.denoised = centre_crop(sample.denoised[0], crop);
        rep.resynthesized = centre_crop(analysis::plane_to_float(resynth.view(), 0), crop);
        rep.title = std::string("filmgrain analyze: ") + (fgc ? "FGC SEI (" + std::string(fgc_flavour_name(flavour)) + ")" : "AV1 film grain");
        rep.input_description = o.input + ": " + std::to_string(info.width) + "x" + std::to_string(info.height) + " " +
                                pix_fmt_name(fmt) + ", " + std::to_string(k) + " frame(s), " +
                                std::to_string(analyzer->frames_analysed()) + " analysed (every " +
                                std::to_string(ao.frame_step) + "), crop from frame " + std::to_string(sample.index);
        rep.notes.push_back(o.denoised.empty()
                                ? (o.spatial ? "denoising: spatial (Gaussian) only; coarse grain is underestimated"
                                             : "denoising: motion-adaptive temporal over +-" + std::to_string(o.temporal_radius) +
                                                   " frames; " + percent(analyzer->reliable_fraction()) +
                                                   " of the flat samples had temporal estimates")
                                : "denoised input supplied: " + o.denoised);
        rep.parameters_text = params_text;
        analysis::write_analysis_report(o.report, rep);
    }
    write_file_atomically(o.output, params_text);
    if (!o.table.empty()) write_file_atomically(o.table, av1_grain_table_text(av1_frames, info.fps_num, info.fps_den));
    if (!o.afgs1.empty() && !av1_frames.empty()) {
        // One AFGS1 T.35 payload carrying the estimated set for pictures of the input's
        // size, subsampling and bit depth (the seed is that of the first picture).
        Afgs1ParamSet set;
        set.params = av1_frames.front();
        set.params.update_grain = 1;
        int log2 = 0;  // the 12-bit resolution fields count units of 1 << log2 samples
        while (((info.width >> log2) >= 4096 || (info.height >> log2) >= 4096) && log2 < 15) log2++;
        set.target.apply_units_resolution_log2 = log2;
        set.target.apply_horz_resolution = info.width >> log2;
        set.target.apply_vert_resolution = info.height >> log2;
        set.target.luma_only_flag = fmt.chroma == ChromaFormat::k400;
        set.target.subsampling_x = set.target.luma_only_flag ? 0 : chroma_shift_x(fmt.chroma);
        set.target.subsampling_y = set.target.luma_only_flag ? 0 : chroma_shift_y(fmt.chroma);
        set.target.bit_depth_minus8 = fmt.bit_depth - 8;
        set.target.video_signal_characteristics_flag = fmt.bit_depth != 8;
        Afgs1Payload payload;
        payload.sets.push_back(set);
        const std::vector<uint8_t> bytes = write_afgs1(payload);
        write_file_atomically(o.afgs1, std::string(bytes.begin(), bytes.end()));
    }
    if (!o.sei.empty()) {
        const std::vector<uint8_t> payload = write_fgc_sei_payload(fgc_params, codec);
        write_file_atomically(o.sei, std::string(payload.begin(), payload.end()));
    }
    if (!o.quiet) {
        std::fprintf(stderr, "filmgrain analyze: %d frame(s), %d analysed; parameters written to %s\n", k,
                     analyzer->frames_analysed(), o.output.c_str());
        for (const auto& p : rep.planes)
            std::fprintf(stderr, "  %s: %s%s\n", p.name.c_str(), p.present ? "" : "no grain; ", p.summary.c_str());
    }
}


void add_analyze_options(CLI::App* sub, AnalyzeOptions& o) {
    sub->add_option("input", o.input, "grainy input (raw planar YUV or Y4M), - for stdin")->required();
    sub->add_option("--denoised", o.denoised, "the input's denoised version (same size and format) instead of the built-in denoiser");
    sub->add_option("--model", o.model, "fgc (FGC SEI frequency-filtering model) or av1 (AV1 / AFGS1)")->required();
    sub->add_option("--output,-o", o.output, "parameter JSON, usable as `filmgrain apply --params`")->required();
    sub->add_option("--table", o.table, "av1: also write a libaom film grain table (filmgrn1)");
    sub->add_option("--afgs1", o.afgs1, "av1: also write an AFGS1 ITU-T T.35 payload (one set for the input's format)");
    sub->add_option("--sei", o.sei, "fgc: also write the FGC SEI payload (payloadType 19 body)");
    sub->add_option("--sei-codec", o.sei_codec, "fgc: SEI syntax variant avc, hevc or vvc")->capture_default_str();
    sub->add_option("--report", o.report, "HTML report; its PNG images are written beside it");
    sub->add_option("--flavour", o.flavour, "fgc: the synthesis the scale is calibrated for, rdd5 or vtm")->capture_default_str();
    sub->add_option("--max-frames", o.max_frames, "analyse about this many pictures, evenly spread")->capture_default_str();
    sub->add_option("--frame-step", o.frame_step, "analyse every Nth picture (0: from --max-frames)")->capture_default_str();
    sub->add_option("--temporal-radius", o.temporal_radius, "neighbours on each side for temporal denoising (0..8)")
        ->capture_default_str();
    sub->add_flag("--spatial", o.spatial, "denoise each picture on its own (spatial fallback only)");
    sub->add_option("--accuracy", o.accuracy,
"relative error the smallest model must meet (intervals / scaling points); 0: the model's default, fgc 0.05, av1 0.02")
        ->capture_default_str();
    sub->add_option("--max-lag", o.max_lag, "av1: longest AR lag considered (0..3)")->capture_default_str();
    sub->add_option("--max-error", o.max_error,
                    "the accuracy check: largest miss of a component's fitted levels, relative, worst intensity band (0..1)")
        ->capture_default_str();
    sub->add_flag("--force", o.force, "write components that fail the accuracy check (refused otherwise)");
    sub->add_flag("--quiet,-q", o.quiet, "no messages on stderr except errors");
    o.raw.add_to(sub);
}

void register_analyze(CLI::App& app) {
    register_subcommand(app, "analyze", "estimate FGC SEI or AV1 film grain parameters from grainy video",
                        add_analyze_options, [](const AnalyzeOptions& o) { return AnalysisJob(o).run(); });
}

#else

void register_analyze(CLI::App& app) {
    CLI::App* sub = app.add_subcommand("analyze", "estimate grain parameters (unavailable: built without OpenCV)");
    sub->allow_extras();
    sub->callback([]() {
        throw Error(ErrorCode::kUnsupported, "analyze needs OpenCV (libopencv-dev); rebuild after tools/install-deps");
    });
}

#endif

}  // namespace filmgrain::cli
