#include "capi/pending_sei_queue.hpp"

#include <string>

#include "filmgrain/error.hpp"

namespace filmgrain::capi {

void PendingSeiQueue::push(PendingSei sei) {
    if (waiting_.size() >= kCapacity)
        throw Error(ErrorCode::kInvalidArgument,
                    std::to_string(kCapacity) +
                        " FGC SEIs already wait for pictures that were never applied (picture ids that match no "
                        "output picture?)");
    waiting_.push_back(std::move(sei));
}

std::optional<PendingSei> PendingSeiQueue::take_for(const FgcPictureIds& ids) {
    auto take = [&](std::size_t i) {
        PendingSei s = std::move(waiting_[i]);
        waiting_.erase(waiting_.begin() + std::ptrdiff_t(i));
        return s;
    };
    for (std::size_t i = 0; i < waiting_.size(); i++)
        if (waiting_[i].picture && waiting_[i].picture->poc == ids.poc &&
            waiting_[i].picture->idr_pic_id == ids.idr_pic_id)
            return take(i);
    for (std::size_t i = 0; i < waiting_.size(); i++)
        if (!waiting_[i].picture) return take(i);
    return std::nullopt;
}

}  // namespace filmgrain::capi
