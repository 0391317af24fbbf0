// The JSON parameter readers as the tool and the C API reach them: the bounded document
// parser (size, nesting depth), the FGC / AV1 / per-frame forms, and then synthesis of a
// small picture with whatever parameters were accepted, so that a value the readers let
// through but the arithmetic cannot carry (a negative scale factor, a wrapped array entry)
// is caught by UBSan here. Only filmgrain::Error may come out; anything else, a crash, a
// leak or a sanitizer report is a finding.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "av1/av1_picture_synthesis.hpp"
#include "core/frame_buffer.hpp"
#include "fgc/fgc_stream_synthesis.hpp"
#include "filmgrain/error.hpp"
#include "metadata/av1_params_json.hpp"
#include "metadata/json_access.hpp"
#include "metadata/params_file.hpp"

namespace {

using namespace filmgrain;

FrameBuffer grey_picture(ChromaFormat chroma, int bit_depth) {
    FrameBuffer f(40, 34, PixelFormat{chroma, bit_depth});
    for (std::size_t i = 0; i < f.byte_size(); i++) f.bytes()[i] = uint8_t(i * 37 + 11);
    if (bit_depth > 8)  // keep 16-bit samples inside the bit depth
        for (std::size_t i = 1; i < f.byte_size(); i += 2) f.bytes()[i] &= uint8_t((1 << (bit_depth - 8)) - 1);
    return f;
}

void synthesize_fgc(const ParamsFile& pf) {
    for (FgcFlavour flavour : {FgcFlavour::kRdd5, FgcFlavour::kVtm, FgcFlavour::kTr}) {
        FgcOptions o;
        o.flavour = flavour;
        o.threads = 1;
        FgcStreamSynthesis synth(o);
        FrameBuffer in = grey_picture(ChromaFormat::k420, flavour == FgcFlavour::kVtm ? 10 : 8);
        FrameBuffer out = in;
        for (std::size_t k = 0; k < pf.frames.size() && k < 3; k++) {
            try {
                if (pf.frames[k].fgc) synth.receive_sei(*pf.frames[k].fgc);
                synth.apply(in.view(), out.view(), FgcPictureIds{int(k), 0});
            } catch (const Error&) {
            }
        }
    }
}

void synthesize_av1(const std::vector<Av1FrameParams>& frames) {
    for (std::size_t k = 0; k < frames.size() && k < 3; k++) {
        const Av1FrameParams& f = frames[k];
        const int bit_depth = f.color ? f.color->bit_depth : 8;
        const ChromaFormat chroma = !f.color                     ? ChromaFormat::k420
                                    : f.color->mono_chrome       ? ChromaFormat::k400
                                    : !f.color->subsampling_x    ? ChromaFormat::k444
                                    : f.color->subsampling_y     ? ChromaFormat::k420
                                                                 : ChromaFormat::k422;
        FrameBuffer in = grey_picture(chroma, bit_depth);
        FrameBuffer out = in;
        try {
            av1::apply_film_grain(f.grain, in.view(), out.view(), f.color ? f.color->matrix_coefficients : 2);
        } catch (const Error&) {
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    nlohmann::json j;
    try {
        j = parse_json_document(data, size, "fuzz input");
    } catch (const Error&) {
        return 0;
    }
    try {
        synthesize_fgc(parse_params_json(j));
    } catch (const Error&) {
    }
    try {
        const auto frames = av1_frame_params_from_json(j);
        (void)av1_frame_params_to_json(frames);
        synthesize_av1(frames);
    } catch (const Error&) {
    }
    return 0;
}
