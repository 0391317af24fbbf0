// FGC SEIs that arrived in decoding order and wait for their picture to be output: a
// decoder with picture reordering receives an SEI with a picture long before it applies
// grain to it. Each SEI is taken by the picture whose ids it was pushed with; those
// pushed without ids by the next picture. When several wait for one picture, the last
// received wins.
#pragma once
#include <cstddef>
#include <optional>
#include <vector>

#include "filmgrain/fgc_params.hpp"

namespace filmgrain::session {

struct PendingSei {
    FgcParams params;
    FgcCodec codec = FgcCodec::kHevc;
    std::optional<FgcPictureIds> picture;
};

class PendingSeiQueue {
public:
    // Bounds the memory a stream that never outputs its pictures can take.
    static constexpr std::size_t kCapacity = 64;

    // Throws Error(kInvalidArgument) when kCapacity SEIs already wait.
    void push(PendingSei sei);
    // The SEI pushed with exactly these ids, else the last pushed without ids; every SEI
    // waiting for this picture leaves the queue.
    std::optional<PendingSei> take_for(const FgcPictureIds& ids);
    void clear() { waiting_.clear(); }
    std::size_t size() const { return waiting_.size(); }

private:
    std::vector<PendingSei> waiting_;
};

}  // namespace filmgrain::session
