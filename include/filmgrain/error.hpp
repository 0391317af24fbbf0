// Errors raised by the C++ core. The C API turns them into codes plus a message;
// nothing in the library aborts the process on bad metadata.
#pragma once
#include <stdexcept>
#include <string>

#include "filmgrain/export.h"

namespace filmgrain {

enum class ErrorCode : int {
    kOk = 0,
    kInvalidArgument = 1,   // caller error: sizes, formats, null planes
    kInvalidParams = 2,     // a parameter set breaks the model's constraints
    kMalformedPayload = 3,  // a metadata payload cannot be parsed
    kUnsupported = 4,       // valid but not implemented by the chosen flavour
    kIo = 5,                // file input/output
    kOutOfMemory = 6,
    kInternal = 7,
};

class FG_API Error : public std::runtime_error {
public:
    Error(ErrorCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
    ErrorCode code() const { return code_; }

private:
    ErrorCode code_;
};

// Helper for the "field=value, allowed range" wording every validator uses.
FG_API std::string out_of_range_message(const std::string& field, long long value, long long lo, long long hi);

}  // namespace filmgrain
