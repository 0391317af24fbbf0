#include "session/parameter_file_feed.hpp"

#include <cctype>
#include <cstdio>
#include <memory>
#include <optional>

#include "io/payload_files.hpp"
#include "metadata/aom_grain_table.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/fgc_sei.hpp"
#include "metadata/json_access.hpp"
#include "metadata/params_file.hpp"

namespace filmgrain::session {
namespace {

bool ends_with(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The first bytes of a file (a form is told by its first non-blank characters; the file
// may be large or endless, so no more is read).
std::string file_head(const std::string& name) {
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(name.c_str(), "rb"), &std::fclose);
    if (!f) throw Error(ErrorCode::kIo, "cannot open '" + name + "' for reading");
    char buf[256];
    return std::string(buf, std::fread(buf, 1, sizeof buf, f.get()));
}

}  // namespace

const char* parameter_form_name(ParameterForm f) {
    switch (f) {
    case ParameterForm::kJson: return "json";
    case ParameterForm::kTable: return "tbl";
    case ParameterForm::kAfgs1: return "afgs1";
    case ParameterForm::kSei: return "sei";
    }
    return "?";
}

ParameterForm parameter_form_from_name(const std::string& name, bool sei_codec_given) {
    if (ends_with(name, ".json")) return ParameterForm::kJson;
    if (ends_with(name, ".tbl")) return ParameterForm::kTable;
    if (ends_with(name, ".sei") || ends_with(name, ".fgc.bin") || sei_codec_given) return ParameterForm::kSei;
    return ParameterForm::kAfgs1;
}

ParameterForm detect_parameter_form(const std::string& name, bool sei_codec_given) {
    if (!io::FilePattern::parse(name)) {
        const std::string head = file_head(name);
        std::size_t i = 0;
        while (i < head.size() && std::isspace((unsigned char)head[i])) ++i;
        if (head.compare(i, 8, "filmgrn1") == 0) return ParameterForm::kTable;
        if (i < head.size() && head[i] == '{') return ParameterForm::kJson;
    }
    // Binary payloads carry no signature of their own: take them only under a name that
    // says what they are, so that a picture or a stream is not read as a payload.
    if (ends_with(name, ".json") || ends_with(name, ".tbl") || ends_with(name, ".sei") || ends_with(name, ".fgc.bin") ||
        ends_with(name, ".bin") || ends_with(name, ".afgs1") || ends_with(name, ".t35") || sei_codec_given)
        return parameter_form_from_name(name, sei_codec_given);
    throw Error(ErrorCode::kInvalidArgument,
                "cannot tell which parameter form '" + name +
                    "' holds: it is neither JSON nor a libaom grain table, and its name does not end in .sei / "
                    ".fgc.bin (FGC SEI payload) or .bin / .afgs1 / .t35 (AFGS1 payload); say --from json|tbl|afgs1|sei");
}

struct ParameterFileFeed::Impl {
    FeedModel model = FeedModel::kFgc;
    ParameterFiles files;
    // FGC: a JSON parameter file, or SEI payload files
    std::optional<ParamsFile> fgc_json;
    std::optional<io::PayloadFiles> payloads;  // sei or afgs1 files
    // FGC SEI files that are not a pattern, parsed once at set-up: every picture receives one
    // of these. A payload that does not parse keeps its error, thrown with the picture it
    // arrives with (so that a caller passing invalid sets through still gets its pictures).
    struct ParsedSei {
        std::optional<FgcParams> params;
        ErrorCode code = ErrorCode::kOk;
        std::string error;
    };
    std::vector<ParsedSei> fixed_sei;

    void parse_fixed_sei() {
        if (payloads->is_pattern()) return;
        const std::vector<std::vector<uint8_t>> all = payloads->all();
        for (std::size_t k = 0; k < all.size(); k++) {
            ParsedSei p;
            try {
                p.params = parse_fgc_sei_payload(all[k], files.sei_codec);
            } catch (const Error& e) {
                p.code = e.code();
                p.error = "'" + payloads->name_for(int(k)) + "': " + e.what();
            }
            fixed_sei.push_back(std::move(p));
        }
    }
    // AV1: a grain table, or JSON frames
    std::optional<AomGrainTable> table;
    std::vector<Av1FrameParams> av1_frames;

    FrameInfo feed_fgc(Session& session, int k) {
        FrameInfo fi;
        fi.ids = FgcPictureIds{k, 0};
        const FgcParams* params = nullptr;
        std::optional<FgcParams> from_pattern;
        if (fgc_json) {
            if (!fgc_json->per_frame) {
                if (fgc_json->frames[0].fgc) params = &*fgc_json->frames[0].fgc;  // one object: every picture
            } else if (std::size_t(k) < fgc_json->frames.size()) {
                const FrameParams& fr = fgc_json->frames[std::size_t(k)];
                if (fr.poc) fi.ids.poc = *fr.poc;
                if (fr.idr_pic_id) fi.ids.idr_pic_id = *fr.idr_pic_id;
                if (fr.pic_offset) fi.ids = FgcPictureIds{*fr.pic_offset, 0};
                if (fr.fgc) params = &*fr.fgc;
            }
        } else if (!payloads->is_pattern()) {
            const std::size_t i = payloads->one_for_every_picture() ? 0 : std::size_t(k);
            if (i < fixed_sei.size()) {
                if (!fixed_sei[i].params) throw Error(fixed_sei[i].code, fixed_sei[i].error);
                params = &*fixed_sei[i].params;
            }
        } else if (const auto bytes = payloads->for_picture(k)) {
            try {
                from_pattern = parse_fgc_sei_payload(*bytes, files.sei_codec);
            } catch (const Error& e) {
                throw Error(e.code(), "'" + payloads->name_for(k) + "': " + e.what());
            }
            params = &*from_pattern;
        }
        if (params) session.receive_fgc_params(*params, files.sei_codec);
        return fi;
    }

    FrameInfo feed_av1(Session& session, int k, int fps_num, int fps_den) {
        Av1FilmGrainParams p;
        int mc = files.matrix_coefficients;
        if (table) {
            if (fps_num <= 0 || fps_den <= 0)
                throw Error(ErrorCode::kInvalidArgument, "grain table '" + files.params + "': the frame rate " +
                                                             std::to_string(fps_num) + "/" + std::to_string(fps_den) +
                                                             " cannot time picture " + std::to_string(k) +
                                                             " (a grain table is indexed by time)");
            // libaom tables are indexed by time in 10 MHz ticks
            const int64_t ts = int64_t(k) * 10000000 * fps_den / fps_num;
            const auto idx = table->find_index(ts);
            if (!idx)
                throw Error(ErrorCode::kInvalidParams, "grain table '" + files.params + "' has no entry for frame " +
                                                           std::to_string(k) + " (timestamp " + std::to_string(ts) + ")");
            p = table->resolved_params(*idx);
        } else {
            const bool single = av1_frames.size() == 1;
            if (!single && std::size_t(k) >= av1_frames.size())
                throw Error(ErrorCode::kInvalidParams, "parameter file '" + files.params + "' lists " +
                                                           std::to_string(av1_frames.size()) +
                                                           " frames but the input has more");
            const Av1FrameParams& fp = av1_frames[single ? 0 : std::size_t(k)];
            p = fp.grain;
            if (mc < 0 && fp.color) mc = fp.color->matrix_coefficients;
        }
        if (mc < 0) mc = 2;  // unspecified
        // a file's set is complete: nothing to load from a reference slot
        p.update_grain = 1;
        session.receive_av1_params(p, 0, mc);
        FrameInfo fi;
        fi.ids.poc = k;
        return fi;
    }

    FrameInfo feed_afgs1(Session& session, int k) {
        if (const auto bytes = payloads->for_picture(k)) {
            try {
                session.receive_afgs1_t35(bytes->data(), bytes->size());
            } catch (const Error& e) {
                throw Error(e.code(), "'" + payloads->name_for(k) + "': " + e.what());
            }
        }
        FrameInfo fi;
        fi.ids.poc = k;
        if (files.matrix_coefficients >= 0) fi.matrix_coefficients = files.matrix_coefficients;
        return fi;
    }
};

ParameterFileFeed::ParameterFileFeed(const ParameterFiles& files) : impl_(std::make_unique<Impl>()) {
    Impl& s = *impl_;
    s.files = files;
    if (int(!files.params.empty()) + int(!files.sei.empty()) + int(!files.afgs1.empty()) != 1)
        throw Error(ErrorCode::kInvalidArgument, "give exactly one of a parameter file, SEI payload files or AFGS1 payload files");
    if (!files.sei.empty()) {
        s.payloads.emplace(files.sei);
        s.parse_fixed_sei();
        return;
    }
    if (!files.afgs1.empty()) {
        s.model = FeedModel::kAfgs1;
        s.payloads.emplace(files.afgs1);
        return;
    }
    // A file neither content nor name tells is read as JSON: its reader bounds what it reads
    // and names what is wrong (a picture, /dev/zero), as `apply --params` always did.
    ParameterForm form = ParameterForm::kJson;
    try {
        form = detect_parameter_form(files.params, files.sei_codec_given);
    } catch (const Error& e) {
        if (e.code() != ErrorCode::kInvalidArgument) throw;
    }
    switch (form) {
    case ParameterForm::kTable:
        s.model = FeedModel::kAv1;
        s.table = read_aom_grain_table(files.params);
        return;
    case ParameterForm::kSei:
        s.payloads.emplace(std::vector<std::string>{files.params});
        s.parse_fixed_sei();
        return;
    case ParameterForm::kAfgs1:
        s.model = FeedModel::kAfgs1;
        s.payloads.emplace(std::vector<std::string>{files.params});
        return;
    case ParameterForm::kJson: break;
    }
    ParamsFile pf = load_params_file(files.params);
    if (!pf.has_fgc() && pf.has_av1()) {
        s.model = FeedModel::kAv1;
        s.av1_frames = av1_frame_params_from_json(read_json_file(files.params));
        if (s.av1_frames.empty())
            throw Error(ErrorCode::kInvalidParams, "parameter file '" + files.params + "' has no AV1 frame");
        return;
    }
    s.fgc_json = std::move(pf);
}

ParameterFileFeed::~ParameterFileFeed() = default;
ParameterFileFeed::ParameterFileFeed(ParameterFileFeed&&) noexcept = default;
ParameterFileFeed& ParameterFileFeed::operator=(ParameterFileFeed&&) noexcept = default;

FeedModel ParameterFileFeed::model() const { return impl_->model; }

FrameInfo ParameterFileFeed::feed(Session& session, int k, int fps_num, int fps_den) {
    switch (impl_->model) {
    case FeedModel::kFgc: return impl_->feed_fgc(session, k);
    case FeedModel::kAv1: return impl_->feed_av1(session, k, fps_num, fps_den);
    case FeedModel::kAfgs1: return impl_->feed_afgs1(session, k);
    }
    return {};
}

}  // namespace filmgrain::session
