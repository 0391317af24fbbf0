// Frame-level pipelining for the tool: one thread reads frame k+1 while the caller's
// thread synthesizes frame k and another writes frame k-1. Frames travel in a fixed ring
// of slots, so memory stays constant whatever the stream length (kSlots input and output
// frames), and frames are synthesized in stream order on the calling thread (the models
// keep per-stream state such as SEI persistence). When a stage fails, the others stop at
// once: the queues are aborted and the reader's wait for input is cancelled
// (ReadCancellation), so an error does not wait for a slow pipe to deliver its next frame.
#pragma once
#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

#include "core/frame_buffer.hpp"
#include "io/input_file.hpp"

namespace filmgrain::cli {

// A blocking queue of slot numbers with two ways to end: close() lets consumers drain
// what is queued; abort() releases everyone at once (an error somewhere).
class SlotQueue {
public:
    void push(int v) {
        {
            std::lock_guard<std::mutex> l(m_);
            q_.push_back(v);
        }
        cv_.notify_one();
    }
    bool pop(int& v) {
        std::unique_lock<std::mutex> l(m_);
        cv_.wait(l, [&] { return aborted_ || closed_ || !q_.empty(); });
        if (aborted_ || q_.empty()) return false;
        v = q_.front();
        q_.pop_front();
        return true;
    }
    void close() {
        {
            std::lock_guard<std::mutex> l(m_);
            closed_ = true;
        }
        cv_.notify_all();
    }
    void abort() {
        {
            std::lock_guard<std::mutex> l(m_);
            aborted_ = true;
        }
        cv_.notify_all();
    }

private:
    std::mutex m_;
    std::condition_variable cv_;
    std::deque<int> q_;
    bool closed_ = false, aborted_ = false;
};

struct FrameSlot {
    FrameBuffer in, out;
};

// read(FrameBuffer&) -> bool (false at the end), synthesize(int k, FrameSlot&),
// write(const FrameBuffer&). Returns the number of frames; rethrows the first error of
// any stage after every thread has stopped. read() runs on a thread of its own under a
// ReadCancellation::Scope: reads through InputFile (VideoReader) are cancelled on failure.
template <typename Read, typename Synthesize, typename Write>
int run_frame_pipeline(Read&& read, Synthesize&& synthesize, Write&& write) {
    constexpr int kSlots = 3;
    FrameSlot slots[kSlots];
    SlotQueue free_slots, read_slots, done_slots;
    for (int i = 0; i < kSlots; i++) free_slots.push(i);
    std::mutex error_mutex;
    std::exception_ptr error;
    ReadCancellation cancel_reads;
    auto fail = [&](std::exception_ptr e) {
        {
            std::lock_guard<std::mutex> l(error_mutex);
            if (!error) error = e;
        }
        free_slots.abort();
        read_slots.abort();
        done_slots.abort();
        cancel_reads.cancel();
    };
    std::thread reader([&] {
        ReadCancellation::Scope cancellable(cancel_reads);
        try {
            int i;
            while (free_slots.pop(i)) {
                if (!read(slots[i].in)) break;
                read_slots.push(i);
            }
            read_slots.close();
        } catch (...) {
            fail(std::current_exception());
        }
    });
    std::thread writer([&] {
        try {
            int i;
            while (done_slots.pop(i)) {
                write(slots[i].out);
                free_slots.push(i);
            }
        } catch (...) {
            fail(std::current_exception());
        }
    });
    int k = 0;
    try {
        int i;
        while (read_slots.pop(i)) {
            synthesize(k, slots[i]);
            done_slots.push(i);
            k++;
        }
        done_slots.close();
    } catch (...) {
        fail(std::current_exception());
    }
    reader.join();
    writer.join();
    if (error) std::rethrow_exception(error);
    return k;
}

}  // namespace filmgrain::cli
