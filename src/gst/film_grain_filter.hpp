// filmgrain: adds film grain to raw video, from the GstFilmGrainMeta filmgrainparse put on
// the decoder's pictures or from parameter files given as properties, through one
// filmgrain::Session per stream.
#pragma once
#include <gst/gst.h>

namespace filmgrain::gst {
GType film_grain_filter_get_type();
}
