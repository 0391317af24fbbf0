// libFuzzer entry for the stream parsers: the first byte picks the codec (and whether
// codec detection runs), the rest is the stream. Every layer a stream goes through in
// `inspect` and `params extract` runs: NAL/OBU framing, SEI, POC, FGC/T.35 payloads,
// the JSON and text reports and the parameter file (AV1: sequence and frame headers, and the
// AFGS1 payloads or frame-header grain turned into per-frame parameters).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bitstream/av1_grain_extraction.hpp"
#include "bitstream/stream_report.hpp"
#include "bitstream/stream_scan.hpp"
#include "filmgrain/error.hpp"

using namespace filmgrain::bitstream;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    if (size < 1) return 0;
    const uint8_t selector = data[0];
    data++;
    size--;
    StreamCodec codec = static_cast<StreamCodec>(selector & 3);
    if (selector & 4) {
        if (auto detected = detect_stream_codec(data, size, "fuzz.bin")) codec = *detected;
    }
    const StreamScan scan = scan_stream(data, size, codec);
    (void)stream_scan_to_json(scan).dump();
    (void)stream_scan_to_text(scan);
    (void)units_in_output_order(scan);
    try {
        std::vector<std::string> warnings;
        if (scan.codec == StreamCodec::kAv1)
            (void)filmgrain::av1_frame_params_to_json(av1_params_from_scan(scan, warnings)).dump();
        else
            (void)params_file_to_json(params_file_from_scan(scan, warnings)).dump();
    } catch (const filmgrain::Error&) {
        // streams without pictures are refused with an error, as the CLI does
    }
    return 0;
}
