#include "session/pending_sei_queue.hpp"

#include <string>

#include "filmgrain/error.hpp"

namespace filmgrain::session {

void PendingSeiQueue::push(PendingSei sei) {
    if (waiting_.size() >= kCapacity)
        throw Error(ErrorCode::kInvalidArgument,
                    std::to_string(kCapacity) +
                        " FGC SEIs already wait for pictures that were never applied (picture ids that match no "
                        "output picture?)");
    waiting_.push_back(std::move(sei));
}

std::optional<PendingSei> PendingSeiQueue::take_for(const FgcPictureIds& ids) {
    auto matches_ids = [&](const PendingSei& s) {
        return s.picture && s.picture->poc == ids.poc && s.picture->idr_pic_id == ids.idr_pic_id;
    };
    auto without_ids = [](const PendingSei& s) { return !s.picture; };
    // Several SEIs for one picture: the last one received is the one in force, as when a
    // decoder hands them over one by one before the picture.
    auto take_last = [&](auto&& pred) -> std::optional<PendingSei> {
        std::optional<PendingSei> last;
        std::vector<PendingSei> kept;
        for (PendingSei& s : waiting_) {
            if (pred(s)) last = std::move(s);
            else kept.push_back(std::move(s));
        }
        waiting_ = std::move(kept);
        return last;
    };
    if (auto s = take_last(matches_ids)) return s;
    return take_last(without_ids);
}

}  // namespace filmgrain::session
