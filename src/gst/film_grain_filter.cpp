// The filmgrain element: a GstBaseTransform working in place. A picture with no grain to add
// leaves as it came (prepare_output_buffer hands the input buffer on: no copy, no write); a
// picture with grain is made writable (a copy only when someone else holds it) and the
// session writes it in place.
//
// Picture ids: from the meta (POC, idr_pic_id) when there is one; otherwise picture k since
// the last stream start or flush gets POC k and idr_pic_id 0 (session/parameter_file_feed:
// what `filmgrain apply` gives frame k).
#include "gst/film_grain_filter.hpp"

#include <gst/base/gstbasetransform.h>
#include <gst/video/video.h>

#include <memory>
#include <optional>
#include <string>

#include "core/thread_pool.hpp"
#include "filmgrain/session.hpp"
#include "gst/film_grain_meta.hpp"
#include "session/parameter_file_feed.hpp"

GST_DEBUG_CATEGORY_STATIC(film_grain_filter_debug);
#define GST_CAT_DEFAULT film_grain_filter_debug

namespace filmgrain::gst {
namespace {

enum {
    kPropParams = 1,
    kPropAfgs1,
    kPropSei,
    kPropSeiCodec,
    kPropFlavour,
    kPropThreads,
    kPropOnInvalid,
    kPropPersistence,
    kPropEnabled,
};

enum OnInvalid { kOnInvalidError = 0, kOnInvalidPassthrough = 1 };

// What the properties say; copied under the object lock when a stream starts.
struct Settings {
    std::string params, afgs1, sei;
    int sei_codec = int(FgcCodec::kHevc);
    int flavour = int(FgcFlavour::kRdd5);
    int threads = 0;
    int on_invalid = kOnInvalidError;
    int persistence = int(FgcPersistence::kReference);
    bool enabled = true;
};

// The streaming thread's state.
struct StreamState {
    Settings settings;
    std::optional<Session> session;
    std::optional<session::ParameterFileFeed> feed;
    GstVideoInfo info;
    bool have_info = false;
    int pictures = 0;        // since the last reset: picture k of the feed
    bool fgc_in_force = false;  // an FGC SEI reached the session: pictures without one may get grain
    bool work = false;       // prepare_output_buffer's decision for the buffer in hand
    std::string last_message;
};

struct GstFilmGrain {
    GstBaseTransform parent;
    Settings* settings;  // guarded by the object lock
    StreamState* state;
};

struct GstFilmGrainClass {
    GstBaseTransformClass parent_class;
};

G_DEFINE_TYPE(GstFilmGrain, fg_filter, GST_TYPE_BASE_TRANSFORM)

#define FG_RAW_FORMATS \
    "{ I420, YV12, I420_10LE, I420_12LE, Y42B, I422_10LE, I422_12LE, Y444, Y444_10LE, Y444_12LE, GRAY8, GRAY16_LE }"

GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS(GST_VIDEO_CAPS_MAKE(FG_RAW_FORMATS)));
GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS(GST_VIDEO_CAPS_MAKE(FG_RAW_FORMATS)));

GType flavour_enum_type() {
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(FgcFlavour::kRdd5), "SMPTE RDD 5 (HM-2020 reference)", "rdd5"},
        {int(FgcFlavour::kVtm), "HM/VTM reference decoders", "vtm"},
        {int(FgcFlavour::kVfgs), "VersatileFilmGrain", "vfgs"},
        {int(FgcFlavour::kTr), "rdd5 plus what TR 23002-9 clause 7 allows beyond the references", "tr"},
        {int(FgcFlavour::kFfmpeg), "what FFmpeg 7.1 outputs (grain on the uncropped picture)", "ffmpeg"},
        {0, nullptr, nullptr}};
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstFilmGrainFlavour", values));
    return type;
}

GType sei_codec_enum_type() {
    static GType type = 0;
    static const GEnumValue values[] = {{int(FgcCodec::kAvc), "H.264 (film_grain_characteristics_repetition_period)", "avc"},
                                        {int(FgcCodec::kHevc), "H.265", "hevc"},
                                        {int(FgcCodec::kVvc), "H.266", "vvc"},
                                        {0, nullptr, nullptr}};
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstFilmGrainSeiCodec", values));
    return type;
}

GType on_invalid_enum_type() {
    static GType type = 0;
    static const GEnumValue values[] = {
        {kOnInvalidError, "post an error naming the field, its value and the allowed range, and stop", "error"},
        {kOnInvalidPassthrough, "post a warning naming the field and pass the picture through unchanged", "passthrough"},
        {0, nullptr, nullptr}};
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstFilmGrainOnInvalid", values));
    return type;
}

GType persistence_enum_type() {
    static GType type = 0;
    static const GEnumValue values[] = {
        {int(FgcPersistence::kReference), "as the reference decoders: the last FGC SEI stays in force", "reference"},
        {int(FgcPersistence::kSemantic), "film_grain_characteristics_persistence_flag as the standards define it", "semantic"},
        {0, nullptr, nullptr}};
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstFilmGrainPersistence", values));
    return type;
}

GstFilmGrain* self_of(GstBaseTransform* t) { return reinterpret_cast<GstFilmGrain*>(t); }

void set_property(GObject* object, guint id, const GValue* value, GParamSpec* pspec) {
    GstFilmGrain* self = reinterpret_cast<GstFilmGrain*>(object);
    GST_OBJECT_LOCK(self);
    Settings& s = *self->settings;
    const char* str = nullptr;
    switch (id) {
    case kPropParams: str = g_value_get_string(value); s.params = str ? str : ""; break;
    case kPropAfgs1: str = g_value_get_string(value); s.afgs1 = str ? str : ""; break;
    case kPropSei: str = g_value_get_string(value); s.sei = str ? str : ""; break;
    case kPropSeiCodec: s.sei_codec = g_value_get_enum(value); break;
    case kPropFlavour: s.flavour = g_value_get_enum(value); break;
    case kPropThreads: s.threads = g_value_get_int(value); break;
    case kPropOnInvalid: s.on_invalid = g_value_get_enum(value); break;
    case kPropPersistence: s.persistence = g_value_get_enum(value); break;
    case kPropEnabled: s.enabled = g_value_get_boolean(value); break;
    default: G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec);
    }
    GST_OBJECT_UNLOCK(self);
}

void get_property(GObject* object, guint id, GValue* value, GParamSpec* pspec) {
    GstFilmGrain* self = reinterpret_cast<GstFilmGrain*>(object);
    GST_OBJECT_LOCK(self);
    const Settings& s = *self->settings;
    switch (id) {
    case kPropParams: g_value_set_string(value, s.params.empty() ? nullptr : s.params.c_str()); break;
    case kPropAfgs1: g_value_set_string(value, s.afgs1.empty() ? nullptr : s.afgs1.c_str()); break;
    case kPropSei: g_value_set_string(value, s.sei.empty() ? nullptr : s.sei.c_str()); break;
    case kPropSeiCodec: g_value_set_enum(value, s.sei_codec); break;
    case kPropFlavour: g_value_set_enum(value, s.flavour); break;
    case kPropThreads: g_value_set_int(value, s.threads); break;
    case kPropOnInvalid: g_value_set_enum(value, s.on_invalid); break;
    case kPropPersistence: g_value_set_enum(value, s.persistence); break;
    case kPropEnabled: g_value_set_boolean(value, s.enabled); break;
    default: G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec);
    }
    GST_OBJECT_UNLOCK(self);
}

void finalize(GObject* object) {
    GstFilmGrain* self = reinterpret_cast<GstFilmGrain*>(object);
    delete self->settings;
    delete self->state;
    G_OBJECT_CLASS(fg_filter_parent_class)->finalize(object);
}

// A new session from the properties as they are now: at start, stream start and flush.
// Throws Error naming what is wrong (an option, a parameter file).
void reset_stream(GstFilmGrain* self) {
    StreamState& st = *self->state;
    GST_OBJECT_LOCK(self);
    st.settings = *self->settings;
    GST_OBJECT_UNLOCK(self);
    st.session.reset();
    st.feed.reset();
    st.pictures = 0;
    st.fgc_in_force = false;
    st.last_message.clear();
    const Settings& s = st.settings;
    SessionOptions so;
    so.flavour = FgcFlavour(s.flavour);
    so.persistence = FgcPersistence(s.persistence);
    so.threads = s.threads;
    so.passthrough_invalid = s.on_invalid == kOnInvalidPassthrough;
    st.session.emplace(so);
    if (!s.params.empty() || !s.afgs1.empty() || !s.sei.empty()) {
        session::ParameterFiles files;
        files.params = s.params;
        if (!s.afgs1.empty()) files.afgs1 = {s.afgs1};
        if (!s.sei.empty()) files.sei = {s.sei};
        files.sei_codec = FgcCodec(s.sei_codec);
        st.feed.emplace(files);
    }
}

// Bad metadata or parameters: an element error (the pipeline stops) or a warning (the
// picture passes unchanged), as on-invalid says.
GstFlowReturn report_invalid(GstFilmGrain* self, const std::string& what) {
    if (self->state->settings.on_invalid == kOnInvalidError) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("%s", what.c_str()), (nullptr));
        return GST_FLOW_ERROR;
    }
    if (what != self->state->last_message) {
        self->state->last_message = what;
        GST_ELEMENT_WARNING(self, STREAM, DECODE, ("%s", what.c_str()), ("the picture passes without grain"));
    }
    return GST_FLOW_OK;
}

gboolean start(GstBaseTransform* t) {
    GstFilmGrain* self = self_of(t);
    try {
        reset_stream(self);
    } catch (const std::exception& e) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("%s", e.what()), (nullptr));
        return FALSE;
    }
    return TRUE;
}

gboolean stop(GstBaseTransform* t) {
    StreamState& st = *self_of(t)->state;
    st.session.reset();
    st.feed.reset();
    st.have_info = false;
    return TRUE;
}

gboolean set_caps(GstBaseTransform* t, GstCaps* incaps, GstCaps*) {
    StreamState& st = *self_of(t)->state;
    st.have_info = gst_video_info_from_caps(&st.info, incaps);
    return st.have_info;
}

gboolean sink_event(GstBaseTransform* t, GstEvent* event) {
    GstFilmGrain* self = self_of(t);
    // start() has just made the session when the first stream starts: a stream start before
    // any picture keeps it (the parameter files are not read twice).
    const bool fresh = self->state->session && self->state->pictures == 0;
    if (GST_EVENT_TYPE(event) == GST_EVENT_FLUSH_STOP || (GST_EVENT_TYPE(event) == GST_EVENT_STREAM_START && !fresh)) {
        try {
            reset_stream(self);
        } catch (const std::exception& e) {
            GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("%s", e.what()), (nullptr));
        }
    }
    return GST_BASE_TRANSFORM_CLASS(fg_filter_parent_class)->sink_event(t, event);
}

bool meta_has_grain(const FilmGrainMetaData& m) {
    return (m.av1_grain && m.av1_grain->apply_grain) || !m.afgs1.empty() || !m.afgs1_error.empty() ||
           !m.fgc_sei.empty();
}

GstFlowReturn prepare_output_buffer(GstBaseTransform* t, GstBuffer* in, GstBuffer** out) {
    StreamState& st = *self_of(t)->state;
    const GstFilmGrainMeta* meta = get_film_grain_meta(in);
    st.work = st.settings.enabled && st.session &&
              ((meta && meta->data && meta_has_grain(*meta->data)) || st.fgc_in_force || (!meta && st.feed));
    if (!st.work) {
        *out = in;
        return GST_FLOW_OK;
    }
    return GST_BASE_TRANSFORM_CLASS(fg_filter_parent_class)->prepare_output_buffer(t, in, out);
}

FrameView frame_view(GstVideoFrame& frame) {
    const GstVideoFormatInfo* fi = frame.info.finfo;
    FrameView v;
    v.format = GST_VIDEO_FORMAT_INFO_IS_GRAY(fi)           ? ChromaFormat::k400
               : GST_VIDEO_FORMAT_INFO_W_SUB(fi, 1) == 0   ? ChromaFormat::k444
               : GST_VIDEO_FORMAT_INFO_H_SUB(fi, 1) == 0   ? ChromaFormat::k422
                                                           : ChromaFormat::k420;
    v.bit_depth = GST_VIDEO_FORMAT_INFO_DEPTH(fi, 0);
    v.width = GST_VIDEO_FRAME_WIDTH(&frame);
    v.height = GST_VIDEO_FRAME_HEIGHT(&frame);
    for (int c = 0; c < v.plane_count(); c++) {
        v.planes[c].data = static_cast<uint8_t*>(GST_VIDEO_FRAME_COMP_DATA(&frame, c));
        v.planes[c].stride = GST_VIDEO_FRAME_COMP_STRIDE(&frame, c);
        v.planes[c].width = GST_VIDEO_FRAME_COMP_WIDTH(&frame, c);
        v.planes[c].height = GST_VIDEO_FRAME_COMP_HEIGHT(&frame, c);
    }
    return v;
}

// Hands the session the picture's metadata; returns the picture's FrameInfo, or nullopt
// when the metadata was refused and the picture passes (on-invalid=passthrough).
std::optional<FrameInfo> feed_session(GstFilmGrain* self, const FilmGrainMetaData* m, GstFlowReturn& flow) {
    StreamState& st = *self->state;
    Session& session = *st.session;
    FrameInfo fi;
    fi.ids.poc = st.pictures;
    if (!m) {
        const int fps_num = st.info.fps_n > 0 ? st.info.fps_n : 25, fps_den = st.info.fps_n > 0 ? st.info.fps_d : 1;
        fi = st.feed->feed(session, st.pictures, fps_num, fps_den);
        st.fgc_in_force = st.feed->model() == session::FeedModel::kFgc;
        return fi;
    }
    if (m->poc) fi.ids = FgcPictureIds{*m->poc, m->idr_pic_id};
    try {
        // The picture's own codec grain first (its AV1 frame header's when it applies, the FGC
        // SEI of its access unit), then AFGS1: as `filmgrain decode`, which takes the grain
        // libav exports for the picture before AFGS1.
        if (m->av1_grain && m->av1_grain->apply_grain) {
            Av1FilmGrainParams p = *m->av1_grain;
            p.update_grain = 1;  // resolved by the parser
            session.receive_av1_params(p, 0, m->matrix_coefficients);
            return fi;
        }
        if (!m->fgc_sei.empty()) {
            const FgcCodec codec = bitstream::fgc_codec(m->codec);
            for (const std::vector<uint8_t>& sei : m->fgc_sei)
                session.receive_fgc_sei_payload(sei.data(), sei.size(), codec, fi.ids);
            st.fgc_in_force = true;
            return fi;
        }
        if (!m->afgs1_error.empty()) {
            flow = report_invalid(self, m->afgs1_error);
            return std::nullopt;
        }
        if (!m->afgs1.empty()) {
            session.receive_afgs1_t35(m->afgs1.data(), m->afgs1.size());
            if (m->codec == bitstream::StreamCodec::kAv1 && m->matrix_coefficients != 2) fi.matrix_coefficients = m->matrix_coefficients;
            return fi;
        }
    } catch (const Error& e) {
        if (e.code() == ErrorCode::kInvalidArgument) throw;  // ours, not the stream's
        flow = report_invalid(self, e.what());
        return std::nullopt;
    }
    return fi;
}

GstFlowReturn transform_ip(GstBaseTransform* t, GstBuffer* buffer) {
    GstFilmGrain* self = self_of(t);
    StreamState& st = *self->state;
    if (!st.work) {
        st.pictures++;
        return GST_FLOW_OK;
    }
    if (!st.have_info) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("no caps before the first picture"), (nullptr));
        return GST_FLOW_NOT_NEGOTIATED;
    }
    const GstFilmGrainMeta* meta = get_film_grain_meta(buffer);
    const FilmGrainMetaData* m = meta ? meta->data : nullptr;
    GstFlowReturn flow = GST_FLOW_OK;
    try {
        const std::optional<FrameInfo> fi = feed_session(self, m, flow);
        st.pictures++;
        if (!fi) return flow;
        GstVideoFrame frame;
        if (!gst_video_frame_map(&frame, &st.info, buffer, GstMapFlags(GST_MAP_READWRITE))) {
            GST_ELEMENT_ERROR(self, RESOURCE, WRITE, ("cannot map the picture for writing"), (nullptr));
            return GST_FLOW_ERROR;
        }
        const FrameView v = frame_view(frame);
        ApplyResult r;
        try {
            r = st.session->apply(v, v, &*fi);
        } catch (...) {
            gst_video_frame_unmap(&frame);
            throw;
        }
        gst_video_frame_unmap(&frame);
        if (r.parameters_refused) return report_invalid(self, r.message);
    } catch (const Error& e) {
        if (e.code() == ErrorCode::kInvalidArgument) {
            GST_ELEMENT_ERROR(self, STREAM, FAILED, ("%s", e.what()), (nullptr));
            return GST_FLOW_ERROR;
        }
        return report_invalid(self, e.what());
    } catch (const std::exception& e) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("%s", e.what()), (nullptr));
        return GST_FLOW_ERROR;
    }
    return GST_FLOW_OK;
}

void install_string(GObjectClass* c, guint id, const char* name, const char* nick, const char* blurb) {
    g_object_class_install_property(
        c, id, g_param_spec_string(name, nick, blurb, nullptr, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS)));
}

void install_enum(GObjectClass* c, guint id, const char* name, const char* nick, const char* blurb, GType type, int def) {
    g_object_class_install_property(
        c, id, g_param_spec_enum(name, nick, blurb, type, def, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS)));
}

void fg_filter_class_init(GstFilmGrainClass* klass) {
    GObjectClass* c = G_OBJECT_CLASS(klass);
    GstElementClass* element_class = GST_ELEMENT_CLASS(klass);
    GstBaseTransformClass* bt = GST_BASE_TRANSFORM_CLASS(klass);
    c->set_property = set_property;
    c->get_property = get_property;
    c->finalize = finalize;
    install_string(c, kPropParams, "params", "Parameter file",
                   "Grain for pictures without a GstFilmGrainMeta: a parameter file in any form `filmgrain params "
                   "convert` reads (JSON FGC or AV1 parameters or a per-frame list, a libaom grain table, an FGC SEI "
                   "payload .sei / .fgc.bin, an AFGS1 payload .bin / .afgs1 / .t35); picture k since the stream "
                   "start gets POC k. Read when the stream starts");
    install_string(c, kPropAfgs1, "afgs1", "AFGS1 payload file",
                   "An AFGS1 ITU-T T.35 payload applied to every picture without a meta (or a pattern such as "
                   "afgs1_%d.bin: picture k's payload)");
    install_string(c, kPropSei, "sei", "FGC SEI payload file",
                   "An FGC SEI payload (payloadType 19 body) applied to every picture without a meta (or a pattern "
                   "such as fgc_%d.bin), in the syntax sei-codec says");
    install_enum(c, kPropSeiCodec, "sei-codec", "SEI syntax", "The SEI syntax of the sei and params payload files",
                 sei_codec_enum_type(), int(FgcCodec::kHevc));
    install_enum(c, kPropFlavour, "flavour", "FGC flavour", "Which reference's FGC SEI synthesis to follow",
                 flavour_enum_type(), int(FgcFlavour::kRdd5));
    g_object_class_install_property(
        c, kPropThreads,
        g_param_spec_int("threads", "Threads",
                         "Stripe threads per picture including the streaming thread (0: every core); the output is "
                         "the same for every count",
                         0, kMaxThreads, 0, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS)));
    install_enum(c, kPropOnInvalid, "on-invalid", "On invalid metadata",
                 "Malformed or out-of-range grain metadata: stop with an error, or warn and pass the picture",
                 on_invalid_enum_type(), kOnInvalidError);
    install_enum(c, kPropPersistence, "persistence", "FGC persistence",
                 "How pictures without an FGC SEI of their own are treated", persistence_enum_type(),
                 int(FgcPersistence::kReference));
    g_object_class_install_property(
        c, kPropEnabled,
        g_param_spec_boolean("enabled", "Enabled", "false: every picture passes unchanged (no copy)", TRUE,
                             GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS)));
    gst_element_class_add_static_pad_template(element_class, &sink_template);
    gst_element_class_add_static_pad_template(element_class, &src_template);
    gst_element_class_set_static_metadata(
        element_class, "Film grain synthesis", "Filter/Effect/Video",
        "Adds standard film grain after a decoder: FGC SEI (H.264/H.265/H.266, RDD 5, HM/VTM, VersatileFilmGrain, "
        "TR 23002-9), AV1 film grain and AFGS1, bit-exact with the reference decoders, from filmgrainparse's meta "
        "or from parameter files",
        "filmgrain");
    bt->start = start;
    bt->stop = stop;
    bt->set_caps = set_caps;
    bt->sink_event = sink_event;
    bt->prepare_output_buffer = prepare_output_buffer;
    bt->transform_ip = transform_ip;
    bt->passthrough_on_same_caps = FALSE;
    bt->transform_ip_on_passthrough = FALSE;
    GST_DEBUG_CATEGORY_INIT(film_grain_filter_debug, "filmgrain", 0, "film grain synthesis");
}

void fg_filter_init(GstFilmGrain* self) {
    self->settings = new Settings();
    self->state = new StreamState();
    gst_base_transform_set_in_place(GST_BASE_TRANSFORM(self), TRUE);
}

}  // namespace

GType film_grain_filter_get_type() { return fg_filter_get_type(); }

}  // namespace filmgrain::gst
