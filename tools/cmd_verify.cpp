// `filmgrain verify`: checks a decoder's grainy output against the session's re-synthesis and,
// where they differ, names the implementation mistake that reproduces the decoder's pictures
// (src/verify). The reference pictures come from a stream (decoded by libav with grain
// exported and the metadata read as `decode` reads it; with an explicit --persistence the FGC
// SEI come from the stream scan with their persistence, which that option then decides) or
// from clean pictures plus the metadata files `apply` reads; the decoder's output is Y4M, raw
// YUV or a per-frame .md5 list.
//
// Alignment: a decoder may drop pictures. A decoded picture that does not match the next
// reference picture is looked for among the next kLookahead ones: exactly, else by a clearly
// smaller error (half); the pictures passed over are reported missing. The rest stays aligned.
//
// Exit status: 0 every picture bit-exact, 1 mismatching or missing pictures, 2 an error.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <fstream>
#include <memory>

#include "cli_common.hpp"
#include "core/thread_pool.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/session.hpp"
#include "io/output_file.hpp"
#include "metadata/fgc_sei.hpp"
#include "option_parsing.hpp"
#include "session/parameter_file_feed.hpp"

#ifdef FILMGRAIN_HAVE_VERIFY
#include "verify/mistake_hypotheses.hpp"
#include "verify/verification_report.hpp"
#endif
#ifdef FILMGRAIN_HAVE_LIBAV
#include "decoded_grain.hpp"
#endif

namespace filmgrain::cli {
namespace {

struct VerifyOptions {
    std::string stream;   // coded stream (libav), or empty with --clean
    std::string decoded;  // the decoder's output: .y4m, raw .yuv or a .md5 list
    std::string clean, params, sei_codec = "hevc";
    std::vector<std::string> sei, afgs1;
    RawVideoOptions raw;  // raw decoded / clean input; default: the reference's size and format
    // persistence "": as `decode` on a stream (FFmpeg's reading), the reference's with --clean
    std::string flavour = "rdd5", persistence, coded_size;
    std::string json, report;
    int threads = 0;
    int diagnose = 8;       // mismatching pictures the hypotheses are tried on
    int list_frames = 20;   // mismatching pictures detailed in the text report
    bool quiet = false;
    bool list_mistakes = false;
    // --simulate ID -o OUT: what a decoder making mistake ID outputs, instead of verifying
    std::string simulate, output;
};

constexpr int kExitMismatch = 1, kExitError = 2;

#ifdef FILMGRAIN_HAVE_VERIFY

constexpr std::size_t kLookahead = 8;

struct ReferencePicture {
    int index = 0;
    FrameBuffer clean, expected;
    verify::PictureFacts facts;
    std::string md5;  // of `expected`, made on first use (.md5 lists: compared up to kLookahead times)

    const std::string& expected_md5() {
        if (md5.empty()) md5 = verify::picture_md5(expected.view());
        return md5;
    }
};

// Fills facts from what the session applied (ApplyResult::applied); `coded` is --coded-size
// (0 x 0 without it), which the session sizes vtm's blocks by and so must the hypotheses.
void facts_from_applied(const ApplyResult& r, FgcFlavour flavour, PictureSize coded, verify::PictureFacts& f) {
    if (!r.applied) return;
    const AppliedGrain& a = *r.applied;
    if (a.model == AppliedGrain::Model::kAv1) {
        f.model = verify::PictureFacts::Model::kAv1;
        f.av1 = a.av1;
        f.matrix_coefficients = a.matrix_coefficients;
    } else if (a.model == AppliedGrain::Model::kFgc) {
        f.model = verify::PictureFacts::Model::kFgc;
        f.fgc.params = a.fgc;
        f.fgc.codec = a.fgc_codec;
        f.fgc.ids = a.fgc_ids;
        f.fgc.flavour = flavour;
        f.fgc.persisted = !a.fgc_own_sei;
        f.fgc.coded_width = coded.width;
        f.fgc.coded_height = coded.height;
    }
}

PictureSize coded_size_of(const VerifyOptions& o) {
    return o.coded_size.empty() ? PictureSize{} : parse_picture_size(o.coded_size, "--coded-size");
}

SessionOptions verify_session_options(const VerifyOptions& o, FgcFlavour flavour) {
    SessionOptions so;
    so.flavour = flavour;
    so.threads = o.threads;
    so.persistence = o.persistence == "semantic" ? FgcPersistence::kSemantic : FgcPersistence::kReference;
    so.report_applied_parameters = true;
    if (!o.coded_size.empty()) {
        const PictureSize cs = parse_picture_size(o.coded_size, "--coded-size");
        so.coded_width = cs.width;
        so.coded_height = cs.height;
    }
    return so;
}

class ReferenceSource {
public:
    virtual ~ReferenceSource() = default;
    virtual bool next(ReferencePicture& pic) = 0;
    virtual std::string name() const = 0;
    virtual int fps_num() const { return 25; }
    virtual int fps_den() const { return 1; }
};

// Clean pictures plus the metadata files `apply` reads, through the same session feed.
class FilesSource final : public ReferenceSource {
public:
    FilesSource(const VerifyOptions& o, FgcFlavour flavour)
        : o_(o), flavour_(flavour), reader_(o.clean, o.raw.to_info()), feed_(files(o)),
          session_(verify_session_options(o, flavour)) {}
    bool next(ReferencePicture& pic) override {
        if (!reader_.read(pic.clean)) return false;
        pic.index = k_;
        pic.facts = {};
        const FrameInfo fi = feed_.feed(session_, k_++, reader_.info().fps_num, reader_.info().fps_den);
        pic.expected = FrameBuffer::uninitialized(pic.clean.width(), pic.clean.height(), pic.clean.format());
        const ApplyResult r = session_.apply(pic.clean.view(), pic.expected.view(), &fi);
        facts_from_applied(r, flavour_, coded_size_of(o_), pic.facts);
        return true;
    }
    std::string name() const override { return o_.clean; }
    int fps_num() const override { return reader_.info().fps_num; }
    int fps_den() const override { return reader_.info().fps_den; }

private:
    static session::ParameterFiles files(const VerifyOptions& o) {
        if (int(!o.params.empty()) + int(!o.sei.empty()) + int(!o.afgs1.empty()) != 1)
            throw Error(ErrorCode::kInvalidArgument, "with --clean, give exactly one of --params, --sei or --afgs1");
        session::ParameterFiles f;
        f.params = o.params;
        f.sei = o.sei;
        f.afgs1 = o.afgs1;
        f.sei_codec = parse_fgc_codec(o.sei_codec);
        return f;
    }
    const VerifyOptions& o_;
    FgcFlavour flavour_;
    VideoReader reader_;
    session::ParameterFileFeed feed_;
    Session session_;
    int k_ = 0;
};

#ifdef FILMGRAIN_HAVE_LIBAV
// A coded stream: libav's pictures with grain exported, the grain as `decode` applies it,
// and from the elementary stream's scan what libav does not export (POC and idr_pic_id apart,
// whether a picture brought its own SEI, AV1 show_existing_frame and reference slots, AFGS1).
// With an explicit --persistence, FGC SEI come from the scan, each with its own picture:
// FFmpeg exports an SEI only for the pictures its persistence reading gives it to (FFmpeg 5.1:
// an H.264 repetition_period 0 ends with its picture) and without the flag, where the
// reference (HM) reuses the last SEI. Without it the reference is what `decode` writes.
class StreamSource final : public ReferenceSource {
public:
    StreamSource(const VerifyOptions& o, FgcFlavour flavour)
        : o_(o), flavour_(flavour), decoder_(o.stream, o.threads), session_(verify_session_options(o, flavour)) {
        if (flavour == FgcFlavour::kVfgs)
            throw Error(ErrorCode::kInvalidArgument, "--flavour vfgs: verify checks rdd5, vtm, ffmpeg and tr");
        decoder_.on_damage([this](const libav::DamagedUnit& u) {
            if (!o_.quiet) std::fprintf(stderr, "filmgrain: warning: %s\n", libav::describe(u).c_str());
        });
        stream_ = read_stream_metadata(o.stream, decoder_.description().codec_name, [this](const std::string& w) {
            if (!o_.quiet) std::fprintf(stderr, "filmgrain: warning: %s\n", w.c_str());
        });
        // FGC SEI from the scan when it found any and a persistence was asked for: FFmpeg
        // exports a picture's SEI with its persistence already applied (FFmpeg's way) and
        // without the flag itself.
        if (!o.persistence.empty() && stream_.scan.codec != bitstream::StreamCodec::kAv1)
            for (const bitstream::AccessUnit* u : stream_.units)
                if (u && std::any_of(u->fgc.begin(), u->fgc.end(), [](const auto& f) { return f.params.has_value(); }))
                    fgc_from_scan_ = true;
    }
    bool next(ReferencePicture& pic) override {
        libav::DecodedFrame frame;
        if (!decoder_.next(frame, /*copy_picture=*/true)) return false;
        pic.index = index_++;
        pic.facts = {};
        const bitstream::AccessUnit* unit =
            std::size_t(frame.index) < stream_.units.size() ? stream_.units[std::size_t(frame.index)] : nullptr;
        take_afgs1_grain(frame, stream_.afgs1, frame.picture.width(), frame.picture.height());
        std::optional<FrameInfo> fi =
            fgc_from_scan_ && unit && !frame.av1 ? scanned_fgc_grain(*unit) : hand_exported_grain(session_, frame);
        // the scan's POC and idr_pic_id where they give FFmpeg's seed (RDD 5 pic_offset): the
        // IDR-term hypothesis needs them apart, and vtm seeds from the POC alone
        if (fi && frame.fgc && unit && unit->poc &&
            uint32_t(*unit->poc) + (uint32_t(unit->idr_pic_id.value_or(0)) << 5) == uint32_t(frame.seed))
            fi->ids = FgcPictureIds{*unit->poc, unit->idr_pic_id.value_or(0)};
        else if (fi && frame.fgc)
            fi->ids = FgcPictureIds{int(frame.seed), 0};  // the scan does not give FFmpeg's seed: FFmpeg's
        pic.clean = std::move(frame.picture);
        pic.expected = FrameBuffer::uninitialized(pic.clean.width(), pic.clean.height(), pic.clean.format());
        if (!fi) {
            copy_frame(pic.clean.view(), pic.expected.view());
            return true;
        }
        const ApplyResult r = session_.apply(pic.clean.view(), pic.expected.view(), &*fi);
        facts_from_applied(r, flavour_, coded_size_of(o_), pic.facts);
        if (pic.facts.model == verify::PictureFacts::Model::kAv1) {
            if (unit) {
                pic.facts.av1_show_existing_frame = unit->av1_show_existing_frame;
                pic.facts.av1_other_slots = unit->av1_other_slot_grain;
            }
            pic.facts.av1_previous = previous_av1_;
            previous_av1_ = pic.facts.av1;
        } else if (pic.facts.model == verify::PictureFacts::Model::kFgc && unit) {
            pic.facts.fgc.persisted = unit->fgc.empty();
        }
        return true;
    }
    std::string name() const override { return o_.stream; }
    int fps_num() const override { return decoder_.description().fps_num; }
    int fps_den() const override { return decoder_.description().fps_den; }

private:
    // The picture's own FGC SEI from the scan (the last one that parsed), with its
    // persistence_flag / repetition_period, so that the session's persistence (--persistence:
    // the reference reuses the last SEI; semantic ends it with its picture) decides over
    // pictures without one. nullopt before the stream's first SEI.
    std::optional<FrameInfo> scanned_fgc_grain(const bitstream::AccessUnit& unit) {
        const bitstream::FoundFgc* own = nullptr;
        for (const bitstream::FoundFgc& f : unit.fgc)
            if (f.params) own = &f;
        if (own) {
            session_.receive_fgc_params(*own->params, bitstream::fgc_codec(stream_.scan.codec));
            fgc_seen_ = true;
        }
        if (!fgc_seen_) return std::nullopt;
        FrameInfo fi;
        fi.ids = FgcPictureIds{unit.poc.value_or(0), unit.idr_pic_id.value_or(0)};
        return fi;
    }

    const VerifyOptions& o_;
    FgcFlavour flavour_;
    libav::VideoDecoder decoder_;
    Session session_;
    StreamMetadata stream_;  // its units point into its own scan (moved with it)
    bool fgc_from_scan_ = false, fgc_seen_ = false;
    std::optional<Av1FilmGrainParams> previous_av1_;
    int index_ = 0;
};
#endif

// The decoder's pictures: Y4M / raw YUV, or one MD5 per picture (a line's first 32 hex
// digits; blank lines and '#' comments skipped).
class DecodedInput {
public:
    DecodedInput(const std::string& path, bool md5) : path_(path), md5_(md5) {
        if (!md5) return;
        std::ifstream in(path);
        if (!in) throw Error(ErrorCode::kIo, "cannot read the MD5 list '" + path + "'");
        std::string line;
        int number = 0;
        while (std::getline(in, line)) {
            number++;
            const std::size_t start = line.find_first_not_of(" \t\r");
            if (start == std::string::npos || line[start] == '#') continue;
            std::string hex = line.substr(start, 32);
            for (char& c : hex) c = char(std::tolower(static_cast<unsigned char>(c)));
            if (hex.size() != 32 || hex.find_first_not_of("0123456789abcdef") != std::string::npos)
                throw Error(ErrorCode::kInvalidArgument, "MD5 list '" + path + "' line " + std::to_string(number) +
                                                             ": '" + line.substr(0, 60) +
                                                             "' does not start with an MD5 (32 hexadecimal digits)");
            hashes_.push_back(hex);
        }
        if (hashes_.empty()) throw Error(ErrorCode::kInvalidArgument, "MD5 list '" + path + "' holds no MD5");
    }
    bool md5() const { return md5_; }
    // raw_info: used for raw YUV only (Y4M describes itself).
    bool next(FrameBuffer& picture, std::string& hash, const VideoInfo& raw_info) {
        if (md5_) {
            if (next_hash_ >= hashes_.size()) return false;
            hash = hashes_[next_hash_++];
            return true;
        }
        if (!reader_) {
            reader_ = std::make_unique<VideoReader>(path_, raw_info);
            // a sample above the bit depth in the output under test is a mismatch to report
            // (the picture is compared and the sample named), not an unreadable file
            reader_->keep_samples_above_bit_depth();
        }
        return reader_->read(picture);
    }

private:
    std::string path_;
    bool md5_;
    std::vector<std::string> hashes_;
    std::size_t next_hash_ = 0;
    std::unique_ptr<VideoReader> reader_;
};

bool is_md5_list(const std::string& path) {
    return path.size() > 4 && path.compare(path.size() - 4, 4, ".md5") == 0;
}

int luma_block_of(const ReferencePicture& pic) {
    if (pic.facts.model == verify::PictureFacts::Model::kFgc) {
        const int bs = verify::fgc_reference_block_size(pic.facts.fgc, pic.clean.width(), pic.clean.height());
        return bs == 32 ? 32 : 16;  // the randomization blocks (TR 23002-9 7.3.2): 16x16, 32x32 at 32
    }
    return 32;  // AV1 7.18.3.5's blocks
}

void check_decoded_shape(const FrameBuffer& decoded, const FrameBuffer& expected, int index) {
    if (decoded.width() != expected.width() || decoded.height() != expected.height() ||
        decoded.format().chroma != expected.format().chroma || decoded.format().bit_depth != expected.format().bit_depth)
        throw Error(ErrorCode::kInvalidArgument,
                    "decoded picture " + std::to_string(index) + " is " + std::to_string(decoded.width()) + "x" +
                        std::to_string(decoded.height()) + " " + pix_fmt_name(decoded.format()) +
                        ", the reference's " + std::to_string(expected.width()) + "x" +
                        std::to_string(expected.height()) + " " + pix_fmt_name(expected.format()) +
                        " (give the decoder's output at the stream's size and format; raw YUV: --size, --pix-fmt)");
}

// The reference output with one mistake made wherever it can change a picture: a "broken
// decoder" to see what the mistake looks like, and what the tests verify.
int run_simulate(const VerifyOptions& o, ReferenceSource& source) {
    if (o.output.empty()) throw Error(ErrorCode::kInvalidArgument, "--simulate needs --output FILE");
    const std::vector<std::string> ids = verify::hypothesis_ids();
    if (std::find(ids.begin(), ids.end(), o.simulate) == ids.end()) {
        std::string allowed;
        for (const std::string& id : ids) allowed += (allowed.empty() ? "" : ", ") + id;
        throw Error(ErrorCode::kInvalidArgument, "--simulate '" + o.simulate + "' is not a known mistake (allowed " + allowed + ")");
    }
    std::unique_ptr<VideoWriter> writer;
    FrameBuffer out;
    ReferencePicture pic;
    int pictures = 0, changed = 0;
    while (source.next(pic)) {
        if (!writer) {
            VideoInfo info;
            info.width = pic.clean.width();
            info.height = pic.clean.height();
            info.format = pic.clean.format();
            info.fps_num = source.fps_num();
            info.fps_den = source.fps_den();
            writer = std::make_unique<VideoWriter>(o.output, info, o.output == "-" || has_y4m_extension(o.output));
        }
        out = FrameBuffer::uninitialized(pic.clean.width(), pic.clean.height(), pic.clean.format());
        bool made = false;
        for (const verify::Hypothesis& h : verify::picture_hypotheses(pic.facts, pic.clean.view(), o.threads))
            if (h.id == o.simulate) {
                try {
                    h.synthesize(pic.clean.view(), pic.expected.view(), out.view());
                    made = true;
                } catch (const Error& e) {
                    if (!o.quiet)
                        std::fprintf(stderr, "filmgrain: picture %d: %s cannot be made: %s\n", pic.index,
                                     o.simulate.c_str(), e.what());
                }
                break;
            }
        if (!made) copy_frame(pic.expected.view(), out.view());
        changed += made && !verify::picture_distance(out.view(), pic.expected.view()).exact();
        writer->write(out);
        pictures++;
    }
    if (!writer) throw Error(ErrorCode::kIo, "'" + source.name() + "' holds no picture");
    writer->commit();
    if (!o.quiet)
        std::fprintf(stderr, "filmgrain: %d picture(s) written to %s, %d changed by %s\n", pictures, o.output.c_str(),
                     changed, o.simulate.c_str());
    return 0;
}

int run_verify(const VerifyOptions& o) {
    if (o.list_mistakes) {
        for (const std::string& id : verify::hypothesis_ids()) std::printf("%s\n", id.c_str());
        return 0;
    }
    const FgcFlavour flavour = parse_flavour(o.flavour);
    if (!o.persistence.empty() && o.persistence != "reference" && o.persistence != "semantic")
        throw Error(ErrorCode::kInvalidArgument, "--persistence '" + o.persistence + "' is not known (allowed reference, semantic)");
    if (o.stream.empty() == o.clean.empty())
        throw Error(ErrorCode::kInvalidArgument, "give either a STREAM or --clean CLEAN with its metadata");
    if (!o.stream.empty() && (!o.params.empty() || !o.sei.empty() || !o.afgs1.empty()))
        throw Error(ErrorCode::kInvalidArgument, "--params, --sei and --afgs1 go with --clean; a STREAM carries its metadata");
    std::unique_ptr<ReferenceSource> source;
    if (!o.clean.empty()) {
        source = std::make_unique<FilesSource>(o, flavour);
    } else {
#ifdef FILMGRAIN_HAVE_LIBAV
        source = std::make_unique<StreamSource>(o, flavour);
#else
        throw Error(ErrorCode::kUnsupported, "this build of filmgrain has no libav*: verify a STREAM needs it; use --clean");
#endif
    }
    if (!o.simulate.empty()) return run_simulate(o, *source);
    if (o.decoded.empty()) throw Error(ErrorCode::kInvalidArgument, "--decoded FILE is needed (the decoder's output)");
    DecodedInput decoded_input(o.decoded, is_md5_list(o.decoded));
    std::unique_ptr<verify::HeatMapWriter> heat_maps;
    if (!o.report.empty()) heat_maps = std::make_unique<verify::HeatMapWriter>(o.report + ".frames");

    verify::VerificationResult result;
    result.source_name = source->name();
    result.decoded_name = o.decoded;
    std::vector<std::vector<std::string>> contradictions;
    std::deque<ReferencePicture> ahead;
    auto fill = [&](std::size_t n) {
        while (ahead.size() < n) {
            ReferencePicture pic;
            if (!source->next(pic)) return;
            ahead.push_back(std::move(pic));
        }
    };
    auto record_missing = [&](const ReferencePicture& pic) {
        verify::FrameVerification f;
        f.index = pic.index;
        f.missing = true;
        f.grain_expected = pic.facts.grain_expected();
        result.frames.push_back(std::move(f));
        contradictions.emplace_back();
    };
    int diagnosed = 0, decoded_count = 0;
    FrameBuffer decoded;
    std::string decoded_md5;
    // raw YUV output: --size / --pix-fmt, else the reference's (Y4M describes itself)
    VideoInfo raw = o.raw.to_info();
    bool raw_known = !o.raw.size.empty();
    for (;;) {
        fill(1);
        if (!raw_known && !ahead.empty()) {
            raw.width = ahead.front().clean.width();
            raw.height = ahead.front().clean.height();
            raw.format = ahead.front().clean.format();
            raw_known = true;
        }
        if (!decoded_input.next(decoded, decoded_md5, raw)) break;
        const int decoded_index = decoded_count++;
        if (ahead.empty()) {
            result.extra_decoded++;
            continue;
        }
        if (result.frames.empty() && result.width == 0) {
            const ReferencePicture& first = ahead.front();
            result.width = first.clean.width();
            result.height = first.clean.height();
            result.pix_fmt = pix_fmt_name(first.clean.format());
            result.luma_block = luma_block_of(first);
            result.model = first.facts.model == verify::PictureFacts::Model::kAv1   ? "av1"
                           : first.facts.model == verify::PictureFacts::Model::kFgc ? "fgc"
                                                                                    : "none";
            result.reference = result.model == "fgc" ? std::string("fgc ") + fgc_flavour_name(flavour)
                                                     : result.model == "av1" ? "av1 (AV1 7.18.3; AFGS1 sets as AV1)" : "no grain";
        }
        if (!decoded_input.md5()) check_decoded_shape(decoded, ahead.front().expected, decoded_index);
        // A dropped picture: the decoded one is a later reference picture, exactly, else (whole
        // pictures only) with less than half the error of the closest so far.
        const bool md5 = decoded_input.md5();
        auto distance_to = [&](ReferencePicture& pic) {
            return verify::picture_distance(pic.expected.view(), decoded.view());
        };
        const verify::Distance own = md5 ? verify::Distance{} : distance_to(ahead.front());
        std::size_t skip = 0;
        if (md5 ? ahead.front().expected_md5() != decoded_md5 : !own.exact()) {
            fill(kLookahead + 1);
            std::size_t closest = 0;
            double best = own.squared_error;
            for (std::size_t k = 1; k < ahead.size() && !skip; k++) {
                if (md5) {
                    if (ahead[k].expected_md5() == decoded_md5) skip = k;
                    continue;
                }
                const verify::Distance d = distance_to(ahead[k]);
                if (d.exact()) skip = k;
                else if (d.squared_error < 0.5 * best) best = d.squared_error, closest = k;
            }
            if (!skip) skip = closest;
        }
        for (std::size_t k = 0; k < skip; k++) {
            record_missing(ahead.front());
            ahead.pop_front();
        }
        ReferencePicture pic = std::move(ahead.front());
        ahead.pop_front();
        verify::FrameVerification f;
        f.index = pic.index;
        f.decoded_index = decoded_index;
        f.grain_expected = pic.facts.grain_expected();
        if (decoded_input.md5()) {
            f.expected_md5 = pic.expected_md5();
            f.decoded_md5 = decoded_md5;
            f.exact = f.expected_md5 == decoded_md5;
        } else {
            f.comparison = verify::compare_pictures(pic.expected.view(), decoded.view(), result.luma_block);
            f.exact = f.comparison->exact();
            if (!f.exact) f.above_bit_depth = find_sample_above_bit_depth(decoded.view());
        }
        if (f.exact) {
            contradictions.push_back(verify::certain_hypotheses(pic.facts, pic.clean.view()));
        } else {
            contradictions.emplace_back();
            if (diagnosed < o.diagnose) {
                diagnosed++;
                const FrameView d = decoded.view();
                f.hypotheses = verify::judge_hypotheses(pic.facts, pic.clean.view(), pic.expected.view(),
                                                        decoded_input.md5() ? nullptr : &d, decoded_md5, o.threads);
            }
            if (heat_maps && f.comparison && !f.comparison->planes.empty())
                f.heat_map = heat_maps->write(pic.index, decoded.view(), f.comparison->planes[0]);
        }
        result.frames.push_back(std::move(f));
    }
    if (decoded_count == 0) throw Error(ErrorCode::kIo, "'" + o.decoded + "' holds no decoded picture");
    // the decoder output fewer pictures than the stream has
    for (;;) {
        fill(1);
        if (ahead.empty()) break;
        record_missing(ahead.front());
        ahead.pop_front();
    }
    result.diagnosis = verify::diagnose_stream(result.frames, contradictions);
    if (heat_maps) {
        // the HTML names its heat maps relative to itself
        const std::string dir = heat_maps->directory();
        const std::string rel = dir.substr(dir.find_last_of('/') + 1);
        for (verify::FrameVerification& f : result.frames)
            if (!f.heat_map.empty()) f.heat_map = rel + "/" + f.heat_map;
        verify::write_verification_html(o.report, result);
    }
    const bool json_stdout = o.json == "-";
    if (!o.json.empty()) {
        const std::string text = verify::verification_json(result) + "\n";
        if (json_stdout) {
            std::fwrite(text.data(), 1, text.size(), stdout);
        } else {
            OutputFile out(o.json);
            std::fwrite(text.data(), 1, text.size(), out.stream());
            out.commit();
        }
    }
    std::FILE* text_out = json_stdout ? stderr : stdout;
    if (!o.quiet) verify::print_verification_text(text_out, result, o.list_frames);
    std::fprintf(text_out, "%s\n", verify::verification_summary_line(result).c_str());
    return result.all_exact() ? 0 : kExitMismatch;
}

#else

int run_verify(const VerifyOptions&) {
    throw Error(ErrorCode::kUnsupported, "this build of filmgrain has no verification (libpng-dev missing at build time)");
}

#endif

void add_verify_options(CLI::App* sub, VerifyOptions& o) {
    sub->add_option("stream", o.stream,
                    "the coded stream the decoder decoded (AV1, H.264, H.265...; read by libav with grain exported)");
    sub->add_option("--decoded,-d", o.decoded,
                    "the decoder's grainy output: .y4m, raw .yuv (--size/--pix-fmt, default the stream's), or a .md5 "
                    "list (one MD5 per picture)");
    sub->add_option("--clean", o.clean, "clean pictures (.y4m or raw .yuv) instead of a stream, with --params/--sei/--afgs1");
    sub->add_option("--params,-p", o.params, "with --clean: a parameter file (JSON, libaom grain table, per-frame list)");
    sub->add_option("--sei", o.sei, "with --clean: FGC SEI payload file(s), one for all pictures, one per picture or a %d pattern");
    sub->add_option("--afgs1", o.afgs1, "with --clean: AFGS1 T.35 payload file(s), as --sei");
    sub->add_option("--sei-codec", o.sei_codec, "SEI syntax of --sei files: avc, hevc or vvc")->capture_default_str();
    o.raw.add_to(sub);
    sub->add_option("--flavour", o.flavour, "the FGC reference the decoder should match: rdd5, vtm, ffmpeg or tr")
        ->capture_default_str();
    sub->add_option("--persistence", o.persistence,
                    "FGC persistence of the reference: reference (HM reuses the last SEI) or semantic (an SEI ends "
                    "with its picture unless it persists). Default: a STREAM's as `decode` reads it (the grain "
                    "libavcodec exports); with --clean, reference");
    sub->add_option("--coded-size", o.coded_size, "vtm: the SPS coded luma size WxH (HM's block size rule)");
    sub->add_option("--json", o.json, "write the full result as JSON to this file (- for stdout; the text report then goes to stderr)");
    sub->add_option("--report", o.report,
                    "write an HTML report with a heat map of differing blocks per mismatching picture (PNG files in "
                    "REPORT.frames/)");
    sub->add_option("--diagnose", o.diagnose, "mismatching pictures the known mistakes are re-synthesized on")
        ->capture_default_str()
        ->check(CLI::Range(0, 1 << 20));
    sub->add_option("--list-frames", o.list_frames, "mismatching pictures detailed in the text report")
        ->capture_default_str()
        ->check(CLI::Range(0, 1 << 20));
    sub->add_option("--threads", o.threads, "threads of the decoder and of the synthesis (0: all cores)")
        ->check(CLI::Range(0, filmgrain::kMaxThreads));
    sub->add_flag("--quiet,-q", o.quiet, "only the summary line (and --json / --report)");
    sub->add_option("--simulate", o.simulate,
                    "instead of verifying, write what a decoder making this mistake outputs (an id of the diagnosis, "
                    "e.g. av1.no_overlap, fgc.no_deblocking, grain_not_applied) to --output");
    sub->add_option("--output,-o", o.output, "with --simulate: the output (.y4m, or raw .yuv)");
    sub->add_flag("--list-mistakes", o.list_mistakes, "print the id of every mistake verify knows, one per line");
}

}  // namespace

void register_verify(CLI::App& app) {
    register_subcommand(app, "verify",
                        "check a decoder's grainy output against the reference re-synthesis and name the mistake that "
                        "explains a mismatch (exit 0 bit-exact, 1 mismatches, 2 error)",
                        add_verify_options, [](const VerifyOptions& o) {
                            try {
                                return run_verify(o);
                            } catch (const Error& e) {
                                std::fprintf(stderr, "filmgrain: error: %s\n", e.what());
                                return kExitError;
                            } catch (const std::bad_alloc&) {
                                std::fprintf(stderr, "filmgrain: error: out of memory\n");
                                return kExitError;
                            }
                        });
}

}  // namespace filmgrain::cli
