#include "base/ThreadPool.h"

#include <cassert>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;

// How long the caller of run() spins for the workers to finish before it sleeps.
constexpr std::chrono::microseconds kCallerSpin{300};

inline void pause() {
#if defined(__x86_64__)
    _mm_pause();
#else
    std::this_thread::yield();
#endif
}

}  // namespace

ThreadPool::ThreadPool(int threads) {
    assert(threads >= 1 && "ThreadPool: at least the calling thread");
    for (int i = 1; i < threads; ++i) workers_.emplace_back([this, i] { work(i); });
}

ThreadPool::~ThreadPool() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_.store(true, std::memory_order_release);
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
}

void ThreadPool::drain(int worker) {
    for (;;) {
        const std::size_t i = next_.fetch_add(1, std::memory_order_relaxed);
        if (i >= count_) return;
        (*job_)(i, worker);
    }
}

bool ThreadPool::spinFor(std::size_t seen, Clock::time_point deadline, bool warmed) const {
    for (int n = 0;; ++n) {
        if (generation_.load(std::memory_order_acquire) != seen || stop_.load(std::memory_order_acquire)) return true;
        // The clock is read every 64 pauses only.
        if ((n & 63) == 63) {
            if (warmed) deadline = Clock::time_point(Clock::duration(warmUntil_.load(std::memory_order_relaxed)));
            if (Clock::now() >= deadline) return false;
        }
        pause();
    }
}

void ThreadPool::run(std::size_t count, const std::function<void(std::size_t, int)>& fn) {
    if (count == 0) return;
    if (workers_.empty() || count == 1) {
        for (std::size_t i = 0; i < count; ++i) fn(i, 0);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        job_ = &fn;
        count_ = count;
        next_.store(0, std::memory_order_relaxed);
        open_ = true;
        generation_.fetch_add(1, std::memory_order_release);  // wakes spinning workers
    }
    wake_.notify_all();
    drain(0);
    // Every index is taken. Workers that have not joined yet (still waking) never will; wait for
    // those that did.
    {
        std::lock_guard<std::mutex> lock(mutex_);
        open_ = false;
    }
    const Clock::time_point deadline = Clock::now() + kCallerSpin;
    for (int n = 0; active_.load(std::memory_order_acquire) != 0; ++n) {
        if ((n & 63) == 63 && Clock::now() >= deadline) {
            std::unique_lock<std::mutex> lock(mutex_);
            done_.wait(lock, [this] { return active_.load(std::memory_order_acquire) == 0; });
            break;
        }
        pause();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = nullptr;
}

void ThreadPool::warm(std::chrono::microseconds within) {
    if (workers_.empty()) return;
    warmUntil_.store((Clock::now() + within).time_since_epoch().count(), std::memory_order_relaxed);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        ++warmth_;
    }
    wake_.notify_all();
}

void ThreadPool::rest() { warmUntil_.store(0, std::memory_order_relaxed); }

void ThreadPool::work(int worker) {
    std::size_t seen = 0, warmth = 0;
    Clock::time_point spinUntil = Clock::now();  // nothing to spin for before the first job
    bool warmed = false;
    for (;;) {
        // While warm (between warm() and rest()), spin for the next job; then sleep until one
        // comes or warm() wakes this thread to spin again.
        if (!spinFor(seen, spinUntil, warmed)) {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] {
                return stop_.load(std::memory_order_relaxed) || generation_.load(std::memory_order_relaxed) != seen ||
                       warmth_ != warmth;
            });
            if (generation_.load(std::memory_order_relaxed) == seen && !stop_.load(std::memory_order_relaxed)) {
                warmth = warmth_;  // warmed: spin until the time warm() gave
                warmed = true;
                continue;
            }
        }
        if (stop_.load(std::memory_order_acquire)) return;
        // Join the job unless the caller has already taken every index and closed it.
        bool joined = false;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            seen = generation_.load(std::memory_order_relaxed);
            if (open_) {
                active_.fetch_add(1, std::memory_order_relaxed);
                joined = true;
            }
        }
        if (joined) {
            drain(worker);
            if (active_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
                std::lock_guard<std::mutex> lock(mutex_);  // the caller may be about to wait
                done_.notify_one();
            }
        }
        // Warm (between warm() and rest()): spin for the next job; otherwise sleep.
        warmed = true;
        spinUntil = Clock::now();
    }
}

}  // namespace frugal
