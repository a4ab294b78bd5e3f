// A small fork-join pool for the software backend and the occlusion pass: run(n, fn) calls
// fn(i, worker) for i in [0, n) on the pool's workers and the calling thread, and returns when all
// are done. Work is handed out one index at a time from an atomic counter, so tiles of uneven cost
// balance themselves. With one thread everything runs on the caller, in index order.
//
// Waking a sleeping thread costs tens of microseconds, much more in a virtual machine (0.14 ms for
// an empty run() on the 2-core VM of docs/occlusion.md): more than a whole job of the occlusion
// pass. So warm() wakes the workers ahead of runs that are coming, to overlap the wake-up with the
// caller's own work: until the time it gives, or rest(), they spin for the next job instead of
// sleeping. Otherwise a worker sleeps as soon as it has finished a job (a spinning thread would take
// a core from whatever runs next, llvmpipe's threads for one). And run() never waits for a worker
// to wake: once the caller has taken the last index, a worker that has not joined the job yet
// does not join it, and the caller waits (spinning a short while, then sleeping) only for those
// that did.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace frugal {

class ThreadPool {
public:
    // `threads` ≥ 1 in total, the caller included.
    explicit ThreadPool(int threads);
    ~ThreadPool();
    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    int size() const { return int(workers_.size()) + 1; }

    // fn(index, worker) with worker in [0, size()): 0 is the caller.
    void run(std::size_t count, const std::function<void(std::size_t, int)>& fn);

    // Wakes the workers now, to spin for the runs that come within `within` (then they sleep again).
    void warm(std::chrono::microseconds within);
    // Ends the spinning warm() asked for: no more runs are coming.
    void rest();

private:
    void work(int worker);
    void drain(int worker);
    // Spins until the job's generation differs from `seen` (true), or until `deadline`, or when
    // `warmed`, until the time warm() gave (false).
    bool spinFor(std::size_t seen, std::chrono::steady_clock::time_point deadline, bool warmed) const;

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(std::size_t, int)>* job_ = nullptr;
    std::size_t count_ = 0;
    std::atomic<std::size_t> next_{0};
    std::atomic<std::size_t> generation_{0};  // bumped per run(), so a worker takes each job once
    bool open_ = false;                       // workers may still join the current job (under mutex_)
    std::atomic<int> active_{0};              // workers that joined it and are not done
    std::atomic<bool> stop_{false};
    // warm(): workers that wake spin until this time (ticks of steady_clock) for the next job.
    std::atomic<std::chrono::steady_clock::rep> warmUntil_{0};
    std::size_t warmth_ = 0;  // bumped per warm(), under the mutex: wakes the sleepers
};

}  // namespace frugal
