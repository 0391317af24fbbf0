#include "gst/unit_metadata_reader.hpp"

#include <optional>
#include <vector>

#include "bitstream/av1_obu.hpp"
#include "bitstream/sei_messages.hpp"
#include "bitstream/stream_scan.hpp"
#include "filmgrain/error.hpp"
#include "metadata/afgs1.hpp"

namespace filmgrain::gst {

struct UnitMetadataReader::State {
    std::optional<bitstream::NalStreamParser> nal;
    bitstream::Av1StreamParser av1;
    Afgs1Reader afgs1;
    int units = 0;

    // Resolved against the stored sets (decode order) and written back with every set
    // explicit: the payload then means the same to a session that sees the pictures in
    // output order.
    void take_afgs1(const bitstream::AccessUnit& au, FilmGrainMetaData& out) {
        for (const bitstream::FoundT35& t : au.t35) {
            if (!bitstream::is_afgs1_t35(t.t35)) continue;
            try {
                out.afgs1 = write_afgs1_resolved(afgs1.receive(bitstream::t35_bytes(t.t35), true));
                out.afgs1_error.clear();
            } catch (const Error& e) {
                out.afgs1_error = std::string("AFGS1 payload: ") + e.what();
            }
        }
    }

    void take_unit(const bitstream::AccessUnit& au, FilmGrainMetaData& out) {
        for (const bitstream::FoundFgc& f : au.fgc) out.fgc_sei.push_back(f.payload);
        take_afgs1(au, out);
        if (au.poc) out.poc = au.poc;
        if (au.idr_pic_id) out.idr_pic_id = *au.idr_pic_id;
        if (au.av1_frame_grain) out.av1_grain = au.av1_frame_grain;
        for (const std::string& w : au.warnings) out.warnings.push_back(w);
    }
};

UnitMetadataReader::UnitMetadataReader(bitstream::StreamCodec codec) : codec_(codec), state_(std::make_unique<State>()) {
    if (codec != bitstream::StreamCodec::kAv1) state_->nal.emplace(codec);
}

UnitMetadataReader::~UnitMetadataReader() = default;

void UnitMetadataReader::flush() {
    state_->afgs1 = Afgs1Reader{};
    state_->units = 0;
}

FilmGrainMetaData UnitMetadataReader::read(const uint8_t* data, std::size_t size) {
    State& s = *state_;
    FilmGrainMetaData out;
    out.codec = codec_;
    out.decode_index = s.units++;
    std::vector<bitstream::AccessUnit> units;
    try {
        if (s.nal) {
            for (std::string& w : s.nal->push(data, size, 0, units)) out.warnings.push_back(std::move(w));
            s.nal->end_access_unit(units);
        } else {
            bitstream::Av1Stream stream = bitstream::parse_av1_stream(data, size, bitstream::Av1Container::kLowOverhead);
            for (std::string& w : stream.warnings) out.warnings.push_back(std::move(w));
            for (const bitstream::Av1TemporalUnit& tu : stream.units) units.push_back(s.av1.push(tu));
        }
    } catch (const Error& e) {
        out.warnings.push_back(e.what());
    }
    if (units.size() > 1)
        out.warnings.push_back("one buffer held " + std::to_string(units.size()) +
                               " units (the parser should hand over one access unit or temporal unit per buffer)");
    for (const bitstream::AccessUnit& au : units) s.take_unit(au, out);
    if (const auto& seq = s.av1.sequence_header())
        out.matrix_coefficients = seq->matrix_coefficients;
    return out;
}

}  // namespace filmgrain::gst
