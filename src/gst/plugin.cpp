// The filmgrain GStreamer plugin: filmgrainparse and filmgrain (README, "In GStreamer").
#include <gst/gst.h>

#include "gst/film_grain_filter.hpp"
#include "gst/film_grain_meta.hpp"
#include "gst/film_grain_parse.hpp"

namespace {

gboolean plugin_init(GstPlugin* plugin) {
    filmgrain::gst::film_grain_meta_get_info();
    return gst_element_register(plugin, "filmgrainparse", GST_RANK_NONE, filmgrain::gst::film_grain_parse_get_type()) &&
           gst_element_register(plugin, "filmgrain", GST_RANK_NONE, filmgrain::gst::film_grain_filter_get_type());
}

}  // namespace

#define PACKAGE "filmgrain"
GST_PLUGIN_DEFINE(GST_VERSION_MAJOR, GST_VERSION_MINOR, filmgrain,
                  "Standard film grain after a decoder: FGC SEI, AV1 and AFGS1 metadata and synthesis", plugin_init,
                  "2.0.0", GST_LICENSE_UNKNOWN, "filmgrain", "https://github.com/filmgrain")
