// A small fork-join pool for stripe-parallel synthesis. Each synthesis context owns one (no
// process-wide pool), so contexts stay independent. The calling thread works too, so a pool
// of size 1 starts no thread at all and runs everything inline.
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace filmgrain {

// The one limit on worker threads for every entry point (C API, C++ API, every --threads
// of the tool): 0..kMaxThreads, 0 = every hardware thread. A stripe is 32 luma rows (AV1)
// or one block row (FGC): even an 8K picture has fewer stripes than this, so more workers
// could never all be busy.
inline constexpr int kMaxThreads = 256;

// 0 means every hardware thread; negative counts are treated as 1.
int resolve_thread_count(int requested);

class ThreadPool {
public:
    explicit ThreadPool(int threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    // Workers including the caller.
    int size() const { return int(workers_.size()) + 1; }

    // Calls fn(task, worker) for every task in [0, tasks), worker in [0, size()), and returns
    // when all are done. Tasks are handed out in increasing order from a shared counter. The
    // first exception thrown by a task is rethrown here after the others have finished.
    // No heap allocation: the callable is passed by address.
    template <typename Fn>
    void parallel_for(int tasks, Fn&& fn) {
        run(tasks, [](void* ctx, int task, int worker) { (*static_cast<std::remove_reference_t<Fn>*>(ctx))(task, worker); },
            const_cast<void*>(static_cast<const void*>(&fn)));
    }

private:
    using Trampoline = void (*)(void*, int, int);
    void run(int tasks, Trampoline call, void* ctx);
    void worker_loop(int worker);
    void work(int worker);

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable start_cv_, done_cv_;
    // Written under mutex_; atomic so that a thread may also poll them without it for a
    // short while before sleeping (see worker_loop and run).
    std::atomic<uint64_t> generation_{0};
    std::atomic<bool> stopping_{false};
    std::atomic<int> busy_{0};
    // the job in flight
    Trampoline call_ = nullptr;
    void* ctx_ = nullptr;
    int tasks_ = 0;
    int next_ = 0;  // guarded by mutex_: tasks are coarse (a stripe), so a lock per task is cheap
    std::exception_ptr error_;
};

}  // namespace filmgrain
