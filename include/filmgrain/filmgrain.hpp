// filmgrain C++ API: the stream session (session.hpp) that the C API (filmgrain.h) is a
// shell over, with its frames (frame.hpp), parameter sets (fgc_params.hpp, av1_params.hpp)
// and errors (error.hpp, thrown as filmgrain::Error carrying an ErrorCode and a message that
// names the field, its value and the allowed range).
#pragma once
#include "filmgrain/av1_params.hpp"
#include "filmgrain/error.hpp"
#include "filmgrain/fgc_params.hpp"
#include "filmgrain/frame.hpp"
#include "filmgrain/session.hpp"
