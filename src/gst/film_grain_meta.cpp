#include "gst/film_grain_meta.hpp"

namespace filmgrain::gst {
namespace {

gboolean meta_init(GstMeta* meta, gpointer, GstBuffer*) {
    reinterpret_cast<GstFilmGrainMeta*>(meta)->data = nullptr;
    return TRUE;
}

void meta_free(GstMeta* meta, GstBuffer*) {
    auto* m = reinterpret_cast<GstFilmGrainMeta*>(meta);
    delete m->data;
    m->data = nullptr;
}

// Copies travel with the buffer (GstVideoDecoder's copy of input metas to the output frame,
// gst_buffer_copy). A region copy or a scaling transform keeps the metadata too: it
// describes the picture, not its samples.
gboolean meta_transform(GstBuffer* dest, GstMeta* meta, GstBuffer*, GQuark, gpointer) {
    const auto* m = reinterpret_cast<const GstFilmGrainMeta*>(meta);
    if (!m->data) return TRUE;
    return add_film_grain_meta(dest, *m->data) != nullptr;
}

}  // namespace

GType film_grain_meta_api_get_type() {
    static GType type = 0;
    static const gchar* tags[] = {nullptr};  // no tags: decoders and converters copy it
    if (g_once_init_enter(&type)) {
        const GType t = gst_meta_api_type_register("GstFilmGrainMetaAPI", tags);
        g_once_init_leave(&type, t);
    }
    return type;
}

const GstMetaInfo* film_grain_meta_get_info() {
    static const GstMetaInfo* info = nullptr;
    if (g_once_init_enter(&info)) {
        const GstMetaInfo* i = gst_meta_register(film_grain_meta_api_get_type(), "GstFilmGrainMeta",
                                                 sizeof(GstFilmGrainMeta), meta_init, meta_free, meta_transform);
        g_once_init_leave(&info, i);
    }
    return info;
}

GstFilmGrainMeta* add_film_grain_meta(GstBuffer* buffer, const FilmGrainMetaData& data) {
    auto* m = reinterpret_cast<GstFilmGrainMeta*>(gst_buffer_add_meta(buffer, film_grain_meta_get_info(), nullptr));
    if (!m) return nullptr;
    m->data = new FilmGrainMetaData(data);
    return m;
}

}  // namespace filmgrain::gst
