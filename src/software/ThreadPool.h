// A small fork-join pool for the software backend: run(n, fn) calls fn(i, worker) for i in [0, n) on
// the pool's workers and the calling thread, and returns when all are done. Work is handed out one
// index at a time from an atomic counter, so tiles of uneven cost balance themselves. With one
// thread everything runs on the caller, in index order.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace frugal::sw {

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

private:
    void work(int worker);
    void drain(int worker);

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(std::size_t, int)>* job_ = nullptr;
    std::size_t count_ = 0;
    std::atomic<std::size_t> next_{0};
    std::size_t generation_ = 0;  // bumped per run(), so a worker takes each job once
    int busy_ = 0;                // workers still inside the current job
    bool stop_ = false;
};

}  // namespace frugal::sw
