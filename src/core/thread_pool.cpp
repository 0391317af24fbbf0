#include "core/thread_pool.hpp"

#include <algorithm>
#include <chrono>

namespace filmgrain {

int resolve_thread_count(int requested) {
    if (requested > 0) return requested;
    if (requested < 0) return 1;
    const unsigned hw = std::thread::hardware_concurrency();
    return hw ? int(hw) : 1;
}

ThreadPool::ThreadPool(int threads) {
    const int n = resolve_thread_count(threads);
    workers_.reserve(std::size_t(n - 1));
    for (int w = 1; w < n; w++) workers_.emplace_back([this, w] { worker_loop(w); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    start_cv_.notify_all();
    for (auto& t : workers_) t.join();
}

void ThreadPool::work(int worker) {
    for (;;) {
        int task;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (next_ >= tasks_) return;
            task = next_++;
        }
        try {
            call_(ctx_, task, worker);
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex_);
            if (!error_) error_ = std::current_exception();
            next_ = tasks_;  // stop handing out work
        }
    }
}

namespace {
// Frames come back to back in a decoder or a benchmark, and waking a sleeping thread takes
// tens of microseconds (more in a VM) — a large part of a 1080p frame's 0.3-0.5 ms. So a
// thread polls for the next job or for the end of the current one for this long before it
// blocks; frames further apart cost at most this much polling each.
constexpr auto kPollBeforeSleep = std::chrono::microseconds(60);

template <typename Done>
void poll_briefly(Done done) {
    const auto until = std::chrono::steady_clock::now() + kPollBeforeSleep;
    while (!done() && std::chrono::steady_clock::now() < until) std::this_thread::yield();
}
}  // namespace

void ThreadPool::worker_loop(int worker) {
    uint64_t seen = 0;
    for (;;) {
        poll_briefly([&] { return stopping_.load() || generation_.load() != seen; });
        {
            std::unique_lock<std::mutex> lock(mutex_);
            start_cv_.wait(lock, [&] { return stopping_ || generation_ != seen; });
            if (stopping_) return;
            seen = generation_;
        }
        work(worker);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (--busy_ == 0) done_cv_.notify_all();
        }
    }
}

void ThreadPool::run(int tasks, Trampoline call, void* ctx) {
    if (tasks <= 0) return;
    if (workers_.empty() || tasks == 1) {
        for (int t = 0; t < tasks; t++) call(ctx, t, 0);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        call_ = call;
        ctx_ = ctx;
        tasks_ = tasks;
        next_ = 0;
        error_ = nullptr;
        busy_ = int(workers_.size());
        generation_++;
    }
    start_cv_.notify_all();
    work(0);
    // The others have at most one task left: poll for them before sleeping.
    poll_briefly([&] { return busy_.load() == 0; });
    std::exception_ptr err;
    {
        std::unique_lock<std::mutex> lock(mutex_);
        done_cv_.wait(lock, [&] { return busy_ == 0; });
        err = error_;
        error_ = nullptr;
    }
    if (err) std::rethrow_exception(err);
}

}  // namespace filmgrain
