// The grain metadata of each access unit (H.26x, Annex B) or temporal unit (AV1 OBUs) as a
// parser element hands the units over, in decode order: the library's stream parsers
// (bitstream/stream_scan.hpp) for POC, SEI, OBUs and frame headers, and the AFGS1 stored
// sets, which only decode order resolves correctly.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>

#include "gst/film_grain_meta.hpp"

namespace filmgrain::gst {

class UnitMetadataReader {
public:
    explicit UnitMetadataReader(bitstream::StreamCodec codec);
    ~UnitMetadataReader();

    // One unit; several in one buffer are read as one (their FGC SEIs and AFGS1 payloads in
    // order, the last picture's ids), with a warning. Never throws for stream content:
    // damage becomes warnings or afgs1_error.
    FilmGrainMetaData read(const uint8_t* data, std::size_t size);
    // After a flush (seek): the AFGS1 stored sets are forgotten, as a decoder starting at
    // this point would not have them; parameter sets and sequence headers stay.
    void flush();
    bitstream::StreamCodec codec() const { return codec_; }

private:
    struct State;
    bitstream::StreamCodec codec_;
    std::unique_ptr<State> state_;
};

}  // namespace filmgrain::gst
