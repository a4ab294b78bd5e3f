// SIGINT, SIGTERM and SIGHUP as io/Interrupt.h handles them, each case in a child process (a death
// test): the handler is installed there, and the child must end by the signal with exactly the
// stderr given.
#include <pthread.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <thread>

#include <gtest/gtest.h>

#include "io/Interrupt.h"

namespace frugal {
namespace {

using ::testing::ExitedWithCode;
using ::testing::KilledBySignal;

// The handler as a process started from a terminal gets it: a test run by nohup or as a background
// job inherits SIGHUP or SIGINT ignored, which installInterruptHandler rightly leaves ignored.
void installAsStartedFromATerminal() {
    for (int signal : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal, SIG_DFL);
    installInterruptHandler();
}

TEST(InterruptTest, OutsidePointsASignalStopsAtOnceWithOneLine) {
    EXPECT_EXIT(
        {
            installAsStartedFromATerminal();
            raise(SIGTERM);
            std::fputs("not reached\n", stderr);
            std::_Exit(0);
        },
        KilledBySignal(SIGTERM), "^error: interrupted by SIGTERM\n$");
}

TEST(InterruptTest, ASignalDuringAWriteWaitsForTheWriteToEnd) {
    EXPECT_EXIT(
        {
            installAsStartedFromATerminal();
            {
                const SignalsHeld held;
                raise(SIGINT);
                std::fputs("the write ended\n", stderr);
            }
            std::fputs("not reached\n", stderr);
            std::_Exit(0);
        },
        KilledBySignal(SIGINT), "^the write ended\nerror: interrupted by SIGINT\n$");
}

// The kernel may hand a process's signal to any of its threads (llvmpipe's, the thread pool's): the
// handler passes it to the main thread, which is writing here, so it waits for the write.
TEST(InterruptTest, ASignalOnAnotherThreadWaitsForTheMainThreadsWrite) {
    EXPECT_EXIT(
        {
            installAsStartedFromATerminal();
            std::atomic<bool> go{false};
            std::thread worker([&go] {
                while (!go) std::this_thread::yield();
                pthread_kill(pthread_self(), SIGTERM);  // this thread's own, not the main one's
            });
            {
                const SignalsHeld held;  // after the worker started: it does not inherit the block
                go = true;
                worker.join();
                std::fputs("the write ended\n", stderr);
            }
            std::_Exit(0);
        },
        KilledBySignal(SIGTERM), "^the write ended\nerror: interrupted by SIGTERM\n$");
}

TEST(InterruptTest, PointsNoteASignalUntilTheWorkTakesIt) {
    EXPECT_EXIT(
        {
            installAsStartedFromATerminal();
            {
                InterruptPoints points;
                raise(SIGTERM);
                std::fputs("went on\n", stderr);
                if (points.arrived() == SIGTERM) std::fputs("took SIGTERM\n", stderr);
            }
            std::fputs("returned\n", stderr);
            raiseNotedSignal();
            std::_Exit(0);
        },
        KilledBySignal(SIGTERM), "^went on\ntook SIGTERM\nreturned\n$");
}

TEST(InterruptTest, ASignalNotTakenStopsWhenThePointsEnd) {
    EXPECT_EXIT(
        {
            installAsStartedFromATerminal();
            {
                InterruptPoints points;
                raise(SIGHUP);
                std::fputs("went on\n", stderr);
            }
            std::fputs("not reached\n", stderr);
            std::_Exit(0);
        },
        KilledBySignal(SIGHUP), "^went on\nerror: interrupted by SIGHUP\n$");
}

TEST(InterruptTest, ASecondSignalStopsAtOnce) {
    EXPECT_EXIT(
        {
            installAsStartedFromATerminal();
            InterruptPoints points;
            raise(SIGTERM);
            raise(SIGINT);
            std::fputs("not reached\n", stderr);
            std::_Exit(0);
        },
        KilledBySignal(SIGINT), "^error: interrupted by SIGINT\n$");
}

TEST(InterruptTest, ASignalIgnoredAtStartStaysIgnored) {
    EXPECT_EXIT(
        {
            std::signal(SIGINT, SIG_IGN);  // as a shell starts a background job
            installInterruptHandler();
            raise(SIGINT);
            std::fputs("still here\n", stderr);
            std::_Exit(7);
        },
        ExitedWithCode(7), "^still here\n$");
}

TEST(InterruptTest, WithoutTheHandlerNothingIsNotedAndNothingIsRaised) {
    InterruptPoints points;
    EXPECT_EQ(points.arrived(), 0);
    raiseNotedSignal();  // returns: no signal was noted
}

TEST(InterruptTest, TheLineOfASequenceSaysHowFarItGot) {
    EXPECT_EQ(interruptedAfter(SIGTERM, 3, 10), "interrupted by SIGTERM after 3 of 10 frames");
    EXPECT_EQ(interruptedAfter(SIGINT, 0, 1), "interrupted by SIGINT after 0 of 1 frame");
    EXPECT_STREQ(signalName(SIGHUP), "SIGHUP");
    EXPECT_STREQ(signalName(SIGUSR1), "a signal");
}

}  // namespace
}  // namespace frugal
