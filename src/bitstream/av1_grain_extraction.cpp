#include "bitstream/av1_grain_extraction.hpp"

#include <map>
#include <optional>

#include "filmgrain/error.hpp"
#include "bitstream/afgs1_in_stream.hpp"
#include "bitstream/sei_messages.hpp"
#include "metadata/afgs1.hpp"

namespace filmgrain::bitstream {
namespace {

ChromaFormat chroma_of(const Av1SequenceHeader& h) {
    if (h.mono_chrome) return ChromaFormat::k400;
    if (h.subsampling_x && h.subsampling_y) return ChromaFormat::k420;
    return h.subsampling_x ? ChromaFormat::k422 : ChromaFormat::k444;
}

Afgs1Picture picture_of(const Av1SequenceHeader& h) {
    Afgs1Picture p;
    p.width = h.max_frame_width;
    p.height = h.max_frame_height;
    p.format = chroma_of(h);
    p.bit_depth = h.bit_depth;
    // Without a colour description the values are "unspecified": unknown to the
    // selection, which then matches any signalled CICP.
    if (h.color_description_present_flag) {
        p.color_primaries = h.color_primaries;
        p.transfer_characteristics = h.transfer_characteristics;
        p.matrix_coefficients = h.matrix_coefficients;
    }
    p.video_full_range_flag = h.color_range;
    return p;
}

Av1ColorInfo color_of(const Av1SequenceHeader& h, int matrix_coefficients) {
    Av1ColorInfo c;
    c.bit_depth = h.bit_depth;
    c.mono_chrome = h.mono_chrome;
    c.subsampling_x = h.subsampling_x;
    c.subsampling_y = h.subsampling_y;
    c.matrix_coefficients = matrix_coefficients;
    return c;
}

// film_grain_params() of each shown frame, as the scan resolved them.
std::vector<Av1FrameParams> frames_from_frame_headers(const StreamScan& scan, std::vector<std::string>& warnings) {
    std::optional<Av1SequenceHeader> sequence;
    std::vector<Av1FrameParams> frames;
    for (const AccessUnit& u : scan.units) {
        if (u.av1_sequence_header) sequence = u.av1_sequence_header;
        Av1FrameParams f;
        if (sequence) f.color = color_of(*sequence, sequence->matrix_coefficients);
        if (u.av1_frame_grain)
            f.grain = *u.av1_frame_grain;
        else
            warnings.push_back("TU " + std::to_string(u.index) +
                               ": no shown frame's film grain could be read (written with apply_grain = 0)");
        frames.push_back(f);
    }
    return frames;
}

}  // namespace

std::vector<Av1FrameParams> av1_params_from_scan(const StreamScan& scan, std::vector<std::string>& warnings) {
    if (scan.codec != StreamCodec::kAv1)
        throw Error(ErrorCode::kInvalidArgument, "AV1 film grain extraction needs an AV1 stream, not " +
                                                     std::string(stream_codec_name(scan.codec)));
    if (scan.units.empty()) throw Error(ErrorCode::kMalformedPayload, "the stream holds no temporal unit");
    bool any_afgs1 = false, frame_header_grain = false;
    for (const AccessUnit& u : scan.units) {
        for (const FoundT35& t : u.t35) any_afgs1 |= is_afgs1_t35(t.t35);
        if (u.av1_sequence_header) frame_header_grain |= u.av1_sequence_header->film_grain_params_present != 0;
    }
    if (!any_afgs1 && frame_header_grain) return frames_from_frame_headers(scan, warnings);
    if (!any_afgs1) warnings.push_back("no AFGS1 metadata and no film grain in the frame headers: no frame has grain");

    Afgs1Reader reader;
    std::optional<Av1SequenceHeader> sequence;
    std::vector<Av1FrameParams> frames;
    for (const AccessUnit& u : scan.units) {
        const std::string where = "TU " + std::to_string(u.index) + ": ";
        if (u.av1_sequence_header) sequence = u.av1_sequence_header;
        std::optional<Afgs1Payload> payload;
        for (const FoundT35& t : u.t35) {
            if (!is_afgs1_t35(t.t35)) continue;
            if (payload) warnings.push_back(where + "more than one AFGS1 payload; each updates the stored sets, the "
                                                    "last one chooses the frame's set");
            const std::vector<uint8_t> bytes = t35_bytes(t.t35);
            try {
                payload = reader.receive(bytes, true);
            } catch (const Error& e) {
                warnings.push_back(where + "AFGS1 payload skipped: " + e.what());
            }
        }
        Av1FrameParams f;  // apply_grain = 0
        if (sequence) f.color = color_of(*sequence, sequence->matrix_coefficients);
        if (payload) {
            if (!sequence) {
                warnings.push_back(where + "AFGS1 payload before any sequence header: the picture format is "
                                           "unknown, no set is selected");
            } else if (const auto sel = select_afgs1_set(*payload, picture_of(*sequence))) {
                f.grain = sel->params;
                f.color = color_of(*sequence, sel->matrix_coefficients);
            } else if (payload->afgs1_enable_flag) {
                warnings.push_back(where + "no set of the AFGS1 payload fits the " +
                                   std::to_string(sequence->max_frame_width) + "x" +
                                   std::to_string(sequence->max_frame_height) + " " +
                                   std::to_string(sequence->bit_depth) + "-bit picture");
            }
        }
        frames.push_back(f);
    }
    if (frame_header_grain) {
        // Both: a frame whose own header applies grain keeps it, as AV1 decoders (dav1d,
        // libaom) apply it and `decode` and the GStreamer element do; AFGS1 gives the others
        // theirs.
        std::vector<std::string> header_warnings;
        const std::vector<Av1FrameParams> headers = frames_from_frame_headers(scan, header_warnings);
        int kept = 0;
        for (std::size_t k = 0; k < frames.size() && k < headers.size(); k++)
            if (headers[k].grain.apply_grain) {
                frames[k] = headers[k];
                kept++;
            }
        warnings.push_back("the frame headers also carry film grain (film_grain_params_present = 1): the " +
                           std::to_string(kept) + " frame(s) whose header applies grain keep it, AFGS1 gives the "
                           "others theirs");
    }
    return frames;
}

std::vector<std::optional<Afgs1Payload>> afgs1_payloads_in_output_order(const StreamScan& scan,
                                                                         std::vector<std::string>& warnings) {
    std::vector<std::optional<Afgs1Payload>> out;
    std::map<const AccessUnit*, Afgs1Payload> by_unit;
    bool any = false;
    const auto reads = read_afgs1_in_decode_order(scan);
    for (std::size_t k = 0; k < scan.units.size(); k++)
        for (const Afgs1Read& read : reads[k]) {
            any |= !std::holds_alternative<std::monostate>(read);
            if (const auto* p = std::get_if<Afgs1Payload>(&read)) by_unit[&scan.units[k]] = *p;
            if (const auto* why = std::get_if<std::string>(&read))
                warnings.push_back("access unit " + std::to_string(scan.units[k].index) +
                                   ": AFGS1 payload skipped: " + *why);
        }
    if (!any) return out;
    for (const AccessUnit* au : units_in_output_order(scan)) {
        if (!au->output) continue;
        const auto it = by_unit.find(au);
        out.push_back(it == by_unit.end() ? std::nullopt : std::optional<Afgs1Payload>(it->second));
    }
    return out;
}

}  // namespace filmgrain::bitstream
