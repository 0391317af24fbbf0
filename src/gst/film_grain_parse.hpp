// filmgrainparse: between a parser (h264parse / h265parse / av1parse) and a decoder. Passes
// each access unit or temporal unit on and attaches its film grain metadata as a
// GstFilmGrainMeta (film_grain_meta.hpp).
#pragma once
#include <gst/gst.h>

namespace filmgrain::gst {
GType film_grain_parse_get_type();
}
