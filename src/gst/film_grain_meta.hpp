// GstFilmGrainMeta: one access unit's (H.26x) or temporal unit's (AV1) film grain metadata,
// attached by filmgrainparse to the compressed buffer and carried by GstVideoDecoder to the
// decoded picture (the API has no tags, so decoders copy it), where the filmgrain element
// reads it. It carries what the session needs for that picture, already put in picture
// order where the stream's order matters:
//   - FGC SEI payloads as coded, with the picture's POC and idr_pic_id (the seed and the
//     persistence rules are the session's);
//   - AFGS1: the unit's payload resolved against the 8 stored sets in decode order and
//     re-written with every set explicit, so that it means the same whatever order the
//     pictures reach the element in (B-frames);
//   - AV1 frame-header film grain of the shown frame, update_grain = 0 and
//     show_existing_frame already resolved against the reference slots in decode order,
//     and the sequence header's matrix_coefficients.
#pragma once
#include <gst/gst.h>

#include <optional>
#include <string>
#include <vector>

#include "bitstream/stream_scan.hpp"
#include "filmgrain/av1_params.hpp"

namespace filmgrain::gst {

struct FilmGrainMetaData {
    bitstream::StreamCodec codec = bitstream::StreamCodec::kH265;
    std::optional<int> poc;         // H.26x
    int idr_pic_id = 0;             // H.264
    int decode_index = 0;           // the unit's place in decode order since the last reset
    std::vector<std::vector<uint8_t>> fgc_sei;  // payloadType 19 bodies, in stream order
    std::vector<uint8_t> afgs1;                 // resolved, self-contained T.35 payload (or empty)
    std::string afgs1_error;                    // why the unit's AFGS1 payload could not be read
    std::optional<Av1FilmGrainParams> av1_grain;  // the shown frame's, resolved
    int matrix_coefficients = 2;                  // AV1: the sequence header's (2: unspecified)
    std::vector<std::string> warnings;            // damage in the unit (the scanner's words)
};

struct GstFilmGrainMeta {
    GstMeta meta;
    FilmGrainMetaData* data;  // owned
};

GType film_grain_meta_api_get_type();
const GstMetaInfo* film_grain_meta_get_info();

// Attaches a copy of `data` (the buffer must be writable).
GstFilmGrainMeta* add_film_grain_meta(GstBuffer* buffer, const FilmGrainMetaData& data);
inline GstFilmGrainMeta* get_film_grain_meta(GstBuffer* buffer) {
    return reinterpret_cast<GstFilmGrainMeta*>(gst_buffer_get_meta(buffer, film_grain_meta_api_get_type()));
}

}  // namespace filmgrain::gst
