// The fork-join pool of the software backend and the occlusion pass (base/ThreadPool.h): every
// index runs exactly once per run(), run() returns only when all are done, and the spinning and
// warm() never lose a job, run one twice, or keep the pool from shutting down.
#include <atomic>
#include <chrono>
#include <functional>
#include <memory>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "base/ThreadPool.h"

namespace frugal::sw {
namespace {

using namespace std::chrono_literals;

// Runs `count` indices and checks each ran once, on a worker in range, before run() returned.
void expectEachOnce(ThreadPool& pool, std::size_t count) {
    std::vector<std::atomic<int>> hits(count);
    std::atomic<int> badWorker{0};
    pool.run(count, [&](std::size_t i, int worker) {
        hits[i].fetch_add(1, std::memory_order_relaxed);
        if (worker < 0 || worker >= pool.size()) badWorker.fetch_add(1);
    });
    for (std::size_t i = 0; i < count; ++i) ASSERT_EQ(hits[i].load(), 1) << "index " << i << " of " << count;
    EXPECT_EQ(badWorker.load(), 0);
}

TEST(ThreadPoolTest, EveryIndexRunsOnceInRunsBackToBack) {
    for (int threads : {1, 2, 3, 8}) {
        ThreadPool pool(threads);
        EXPECT_EQ(pool.size(), threads);
        // Back to back (the workers are still spinning), and of every size: none, fewer indices than
        // threads, many.
        for (std::size_t count : {0, 1, 2, 3, 5, 64, 1000})
            for (int repeat = 0; repeat < 20; ++repeat) expectEachOnce(pool, count);
    }
}

TEST(ThreadPoolTest, RunsAfterTheWorkersFellAsleep) {
    ThreadPool pool(3);
    for (int repeat = 0; repeat < 3; ++repeat) {
        std::this_thread::sleep_for(5ms);  // longer than any spin: the workers sleep
        expectEachOnce(pool, 100);
    }
}

TEST(ThreadPoolTest, WarmThenRunOrRest) {
    ThreadPool pool(4);
    // A run while the workers spin for it, one after the time warm() gave, and one after rest().
    pool.warm(50ms);
    expectEachOnce(pool, 200);
    pool.warm(1ms);
    std::this_thread::sleep_for(5ms);
    expectEachOnce(pool, 200);
    pool.warm(50ms);
    pool.rest();
    std::this_thread::sleep_for(1ms);
    expectEachOnce(pool, 200);
    // Many warm() calls in a row, then runs.
    for (int i = 0; i < 100; ++i) pool.warm(100us);
    for (int i = 0; i < 10; ++i) expectEachOnce(pool, 17);
}

TEST(ThreadPoolTest, WorkersShareTheWork) {
    // Each index waits until another thread has taken one too, up to a limit: with 2 threads both
    // must take part (a worker that missed the job would leave the caller alone).
    ThreadPool pool(2);
    std::atomic<int> workerTook{0};
    pool.run(2, [&](std::size_t, int worker) {
        if (worker != 0) workerTook.store(1);
        const auto until = std::chrono::steady_clock::now() + 2s;
        while (std::chrono::steady_clock::now() < until && workerTook.load() == 0) std::this_thread::yield();
    });
    EXPECT_EQ(workerTook.load(), 1);
}

TEST(ThreadPoolTest, ALateWorkerNeverTouchesAFinishedJob) {
    // The workers sleep; the caller takes both indices at once and returns before they wake. The
    // job (a lambda on the heap, freed as run() returns) must not be called again, nor read: a
    // late worker that did would count twice here, or read freed memory (which ASan reports).
    ThreadPool pool(4);
    for (int repeat = 0; repeat < 50; ++repeat) {
        if (repeat % 10 == 0) std::this_thread::sleep_for(2ms);  // let the workers fall asleep
        auto hits = std::make_unique<std::atomic<int>[]>(2);
        {
            auto job = std::make_unique<std::function<void(std::size_t, int)>>(
                [&hits](std::size_t i, int) { hits[i].fetch_add(1); });
            pool.run(2, *job);
        }  // the job is freed here
        EXPECT_EQ(hits[0].load(), 1);
        EXPECT_EQ(hits[1].load(), 1);
        std::this_thread::sleep_for(std::chrono::microseconds(200));  // room for a late worker to misbehave
        EXPECT_EQ(hits[0].load() + hits[1].load(), 2);
    }
}

TEST(ThreadPoolTest, ShutsDownWhileWarmOrSpinning) {
    // Destroyed while the workers spin: for a warm() of an hour (a pool that waited for it would
    // hang the test), or after a job. Every pool still ran its jobs.
    std::atomic<int> ran{0};
    for (int repeat = 0; repeat < 20; ++repeat) {
        ThreadPool pool(3);
        if (repeat % 2 == 0) pool.warm(std::chrono::hours(1));
        pool.run(10, [&](std::size_t, int) { ran.fetch_add(1); });
    }
    EXPECT_EQ(ran.load(), 200);
}

}  // namespace
}  // namespace frugal::sw
