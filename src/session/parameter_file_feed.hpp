// Grain metadata from files, handed to a Session picture by picture as a decoder hands over
// a stream's: what `filmgrain apply --params / --sei / --afgs1` and the GStreamer element's
// params / sei / afgs1 properties share. Reading files makes this tool side (not in
// libfilmgrain).
//
// Picture ids: picture k (counted from 0 by the caller) has POC k and idr_pic_id 0, unless a
// per-frame JSON list gives its own (poc, idr_pic_id or pic_offset).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "filmgrain/session.hpp"

namespace filmgrain::session {

// The parameter forms `filmgrain params convert` reads.
enum class ParameterForm { kJson, kTable, kAfgs1, kSei };
const char* parameter_form_name(ParameterForm f);  // "json", "tbl", "afgs1", "sei"
// From the file's first bytes (JSON, "filmgrn1" grain tables), else from its name: .sei /
// .fgc.bin (or `sei_codec_given`) an FGC SEI payload, .bin / .afgs1 / .t35 an AFGS1 payload.
// A per-picture pattern (frame%d.bin) is told by its name. Throws Error(kInvalidArgument)
// when neither tells (binary payloads carry no signature of their own).
ParameterForm detect_parameter_form(const std::string& name, bool sei_codec_given);
// From the name alone (an output file to be written): .json, .tbl, .sei / .fgc.bin (or
// `sei_codec_given`), anything else an AFGS1 payload.
ParameterForm parameter_form_from_name(const std::string& name, bool sei_codec_given);

struct ParameterFiles {
    // One of the three: a parameter file in any form detect_parameter_form() tells; FGC SEI
    // payload files; AFGS1 T.35 payload files (io::PayloadFiles: one for every picture,
    // one per picture, or a pattern).
    std::string params;
    std::vector<std::string> sei;
    std::vector<std::string> afgs1;
    FgcCodec sei_codec = FgcCodec::kHevc;  // the SEI syntax of sei files and FGC JSON
    bool sei_codec_given = false;          // a binary params file is then an FGC SEI payload
    // AV1 / AFGS1: the picture's matrix_coefficients; -1: the file's, else unspecified (2).
    int matrix_coefficients = -1;
};

enum class FeedModel { kFgc, kAv1, kAfgs1 };

class ParameterFileFeed {
public:
    // Reads and checks the files; throws Error naming the file and what is wrong.
    explicit ParameterFileFeed(const ParameterFiles& files);
    ~ParameterFileFeed();
    ParameterFileFeed(ParameterFileFeed&&) noexcept;
    ParameterFileFeed& operator=(ParameterFileFeed&&) noexcept;

    FeedModel model() const;
    // Hands `session` the metadata that arrives with picture k and returns the picture's
    // FrameInfo. fps: the time base of libaom grain tables (10 MHz ticks). Throws Error
    // naming the file when picture k has no parameters where the file must give them.
    FrameInfo feed(Session& session, int k, int fps_num, int fps_den);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace filmgrain::session
