// filmgrainparse. The one change it may make to the coded data: FGC SEI messages are taken
// out of the units it passes to the decoder (strip-fgc-sei, on by default), because
// libavcodec's H.264 / H.265 decoders behind avdec_h264 / avdec_h265 add their own H.274
// grain from them and GStreamer gives no way to ask them for the parameters instead. The
// messages travel in the meta; grain then comes once, from the filmgrain element.
#include "gst/film_grain_parse.hpp"

#include <gst/base/gstbasetransform.h>

#include <memory>
#include <optional>
#include <string>

#include "bitstream/fgc_sei_removal.hpp"
#include "gst/unit_metadata_reader.hpp"

GST_DEBUG_CATEGORY_STATIC(film_grain_parse_debug);
#define GST_CAT_DEFAULT film_grain_parse_debug

namespace filmgrain::gst {
namespace {

enum { kPropStripFgcSei = 1 };

struct GstFilmGrainParse {
    GstBaseTransform parent;
    // Guarded by the object lock: strip_fgc_sei. Streaming thread only: the rest.
    gboolean strip_fgc_sei;
    std::unique_ptr<UnitMetadataReader>* reader;  // heap: GObject instances are C memory
    std::string* last_warning;
};

struct GstFilmGrainParseClass {
    GstBaseTransformClass parent_class;
};

G_DEFINE_TYPE(GstFilmGrainParse, fg_parse, GST_TYPE_BASE_TRANSFORM)

#define FG_CODED_CAPS                                                  \
    "video/x-h264, stream-format = (string) byte-stream, alignment = (string) au; " \
    "video/x-h265, stream-format = (string) byte-stream, alignment = (string) au; " \
    "video/x-h266, stream-format = (string) byte-stream, alignment = (string) au; " \
    "video/x-av1, stream-format = (string) obu-stream, alignment = (string) tu"

GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS(FG_CODED_CAPS));
GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS(FG_CODED_CAPS));

GstFilmGrainParse* self_of(GstBaseTransform* t) { return reinterpret_cast<GstFilmGrainParse*>(t); }

void set_property(GObject* object, guint id, const GValue* value, GParamSpec* pspec) {
    GstFilmGrainParse* self = reinterpret_cast<GstFilmGrainParse*>(object);
    switch (id) {
    case kPropStripFgcSei:
        GST_OBJECT_LOCK(self);
        self->strip_fgc_sei = g_value_get_boolean(value);
        GST_OBJECT_UNLOCK(self);
        break;
    default: G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec);
    }
}

void get_property(GObject* object, guint id, GValue* value, GParamSpec* pspec) {
    GstFilmGrainParse* self = reinterpret_cast<GstFilmGrainParse*>(object);
    switch (id) {
    case kPropStripFgcSei:
        GST_OBJECT_LOCK(self);
        g_value_set_boolean(value, self->strip_fgc_sei);
        GST_OBJECT_UNLOCK(self);
        break;
    default: G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, pspec);
    }
}

void finalize(GObject* object) {
    GstFilmGrainParse* self = reinterpret_cast<GstFilmGrainParse*>(object);
    delete self->reader;
    delete self->last_warning;
    G_OBJECT_CLASS(fg_parse_parent_class)->finalize(object);
}

std::optional<bitstream::StreamCodec> codec_of_caps(GstCaps* caps) {
    if (!caps || gst_caps_get_size(caps) == 0) return std::nullopt;
    const std::string name = gst_structure_get_name(gst_caps_get_structure(caps, 0));
    if (name == "video/x-h264") return bitstream::StreamCodec::kH264;
    if (name == "video/x-h265") return bitstream::StreamCodec::kH265;
    if (name == "video/x-h266") return bitstream::StreamCodec::kH266;
    if (name == "video/x-av1") return bitstream::StreamCodec::kAv1;
    return std::nullopt;
}

gboolean set_caps(GstBaseTransform* t, GstCaps* incaps, GstCaps*) {
    GstFilmGrainParse* self = self_of(t);
    const std::optional<bitstream::StreamCodec> codec = codec_of_caps(incaps);
    if (!codec) return FALSE;
    // New caps of the same codec (a resolution change) keep the stream state.
    if (!*self->reader || (*self->reader)->codec() != *codec) *self->reader = std::make_unique<UnitMetadataReader>(*codec);
    return TRUE;
}

gboolean sink_event(GstBaseTransform* t, GstEvent* event) {
    GstFilmGrainParse* self = self_of(t);
    if (GST_EVENT_TYPE(event) == GST_EVENT_FLUSH_STOP && *self->reader) (*self->reader)->flush();
    if (GST_EVENT_TYPE(event) == GST_EVENT_STREAM_START) self->reader->reset();  // made again by set_caps
    return GST_BASE_TRANSFORM_CLASS(fg_parse_parent_class)->sink_event(t, event);
}

gboolean stop(GstBaseTransform* t) {
    self_of(t)->reader->reset();
    return TRUE;
}

GstFlowReturn transform_ip(GstBaseTransform* t, GstBuffer* buffer) {
    GstFilmGrainParse* self = self_of(t);
    if (!*self->reader) {
        GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, ("no caps before the first buffer"), (nullptr));
        return GST_FLOW_NOT_NEGOTIATED;
    }
    GST_OBJECT_LOCK(self);
    const bool strip = self->strip_fgc_sei;
    GST_OBJECT_UNLOCK(self);
    GstMapInfo map;
    if (!gst_buffer_map(buffer, &map, GST_MAP_READ)) {
        GST_ELEMENT_ERROR(self, RESOURCE, READ, ("cannot map the coded buffer"), (nullptr));
        return GST_FLOW_ERROR;
    }
    try {
        UnitMetadataReader& reader = **self->reader;
        const FilmGrainMetaData data = reader.read(map.data, map.size);
        std::optional<std::vector<uint8_t>> stripped;
        // remove_fgc_sei leaves AV1 alone
        if (strip && !data.fgc_sei.empty()) stripped = bitstream::remove_fgc_sei(reader.codec(), map.data, map.size);
        gst_buffer_unmap(buffer, &map);
        for (const std::string& w : data.warnings) {
            // a damaged stream repeats itself: one message per distinct text in a row
            if (w == *self->last_warning) continue;
            *self->last_warning = w;
            GST_ELEMENT_WARNING(self, STREAM, DECODE, ("%s", w.c_str()), ("unit %d in decode order", data.decode_index));
        }
        // a unit of nothing but FGC SEI (not a real access unit) passes as it is
        if (stripped && !stripped->empty()) {
            auto* owned = new std::vector<uint8_t>(std::move(*stripped));
            GstMemory* mem = gst_memory_new_wrapped(GST_MEMORY_FLAG_READONLY, owned->data(), owned->size(), 0,
                                                    owned->size(), owned,
                                                    [](gpointer p) { delete static_cast<std::vector<uint8_t>*>(p); });
            gst_buffer_replace_all_memory(buffer, mem);
        }
        if (!data.fgc_sei.empty() || !data.afgs1.empty() || !data.afgs1_error.empty() || data.av1_grain || data.poc)
            add_film_grain_meta(buffer, data);
    } catch (const std::exception& e) {
        GST_ELEMENT_ERROR(self, STREAM, FAILED, ("%s", e.what()), (nullptr));
        return GST_FLOW_ERROR;
    }
    return GST_FLOW_OK;
}

void fg_parse_class_init(GstFilmGrainParseClass* klass) {
    GObjectClass* gobject_class = G_OBJECT_CLASS(klass);
    GstElementClass* element_class = GST_ELEMENT_CLASS(klass);
    GstBaseTransformClass* bt_class = GST_BASE_TRANSFORM_CLASS(klass);
    gobject_class->set_property = set_property;
    gobject_class->get_property = get_property;
    gobject_class->finalize = finalize;
    g_object_class_install_property(
        gobject_class, kPropStripFgcSei,
        g_param_spec_boolean("strip-fgc-sei", "Strip FGC SEI",
                             "Take FGC SEI messages (payloadType 19) out of the H.26x units passed on, so that a "
                             "decoder that applies them itself (avdec_h264 / avdec_h265: libavcodec's own H.274 "
                             "grain) does not add grain before filmgrain does; they travel in the meta. false: "
                             "buffers pass unchanged",
                             TRUE, GParamFlags(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS)));
    gst_element_class_add_static_pad_template(element_class, &sink_template);
    gst_element_class_add_static_pad_template(element_class, &src_template);
    gst_element_class_set_static_metadata(
        element_class, "Film grain metadata parser", "Codec/Parser/Video",
        "Attaches each access unit's or temporal unit's film grain metadata (FGC SEI, AFGS1 T.35 in SEI or "
        "metadata OBUs, AV1 frame-header grain) with the picture ids the filmgrain element needs, as a "
        "GstFilmGrainMeta that survives the decoder",
        "filmgrain");
    bt_class->set_caps = set_caps;
    bt_class->sink_event = sink_event;
    bt_class->stop = stop;
    bt_class->transform_ip = transform_ip;
    bt_class->passthrough_on_same_caps = FALSE;
    GST_DEBUG_CATEGORY_INIT(film_grain_parse_debug, "filmgrainparse", 0, "film grain metadata parser");
}

void fg_parse_init(GstFilmGrainParse* self) {
    self->strip_fgc_sei = TRUE;
    self->reader = new std::unique_ptr<UnitMetadataReader>();
    self->last_warning = new std::string();
    gst_base_transform_set_in_place(GST_BASE_TRANSFORM(self), TRUE);
}

}  // namespace

GType film_grain_parse_get_type() { return fg_parse_get_type(); }

}  // namespace filmgrain::gst
