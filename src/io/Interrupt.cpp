#include "io/Interrupt.h"

#include <pthread.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <ctime>

namespace frugal {
namespace {

constexpr int kHandled[] = {SIGINT, SIGTERM, SIGHUP};

// Read and written on the main thread only (the handler runs there), so sig_atomic_t suffices.
volatile std::sig_atomic_t gPolling = 0;  // an InterruptPoints lives
volatile std::sig_atomic_t gNoted = 0;    // the signal it noted
pthread_t gMainThread;

sigset_t handledSet() {
    sigset_t set;
    sigemptyset(&set);
    for (int signal : kHandled) sigaddset(&set, signal);
    return set;
}

// Open WriteWindows, and whether the process is ending (then none opens). Lock-free atomics, so
// the handler may read and write them (signal-safety(7)).
std::atomic<int> gWriting{0};
std::atomic<bool> gEnding{false};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free);

// Waits until no WriteWindow is open, at most two seconds (a write that hangs, on a dead network
// file system, must not keep the process alive). clock_gettime is async-signal-safe.
void waitForWrites() {
    gEnding.store(true);
    timespec start {};
    clock_gettime(CLOCK_MONOTONIC, &start);
    while (gWriting.load() > 0) {
        timespec now {};
        clock_gettime(CLOCK_MONOTONIC, &now);
        if (now.tv_sec - start.tv_sec >= 2) break;
    }
}

// The default action of the three signals handled ends the process; a caught signal cannot be
// passed on otherwise. Async-signal-safe.
[[noreturn]] void endBySignal(int signal) {
    struct sigaction action {};
    action.sa_handler = SIG_DFL;
    sigemptyset(&action.sa_mask);
    sigaction(signal, &action, nullptr);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, signal);
    pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
    raise(signal);
    _exit(128 + signal);  // not reached
}

// "error: interrupted by SIGTERM", then the signal. Async-signal-safe: the line is copied into a
// buffer on the stack and written with one write(2).
[[noreturn]] void stopNow(int signal) {
    waitForWrites();
    char line[64];
    std::size_t length = 0;
    for (const char* part : {"error: interrupted by ", signalName(signal), "\n"})
        for (const char* c = part; *c != '\0' && length < sizeof line; ++c) line[length++] = *c;
    for (std::size_t done = 0; done < length;) {
        const ssize_t n = ::write(STDERR_FILENO, line + done, length - done);
        if (n > 0)
            done += std::size_t(n);
        else if (errno != EINTR)
            break;
    }
    endBySignal(signal);
}

void onSignal(int signal) {
    const int savedErrno = errno;
    if (!pthread_equal(pthread_self(), gMainThread))
        pthread_kill(gMainThread, signal);  // handled there
    else if (gPolling && gNoted == 0)
        gNoted = signal;
    else
        stopNow(signal);
    errno = savedErrno;
}

}  // namespace

void installInterruptHandler() {
    gMainThread = pthread_self();
    struct sigaction action {};
    action.sa_handler = onSignal;
    action.sa_mask = handledSet();  // one handler at a time
    action.sa_flags = SA_RESTART;   // a noted signal must not fail the read or write it came in
    for (int signal : kHandled) {
        struct sigaction old {};
        if (sigaction(signal, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        sigaction(signal, &action, nullptr);
    }
    // A file that grows past `ulimit -f` then fails its write with EFBIG (one error line, the
    // temporary file removed) instead of SIGXFSZ's core dump.
    std::signal(SIGXFSZ, SIG_IGN);
}

SignalsHeld::SignalsHeld() {
    const sigset_t set = handledSet();
    pthread_sigmask(SIG_BLOCK, &set, &previous_);
}

SignalsHeld::~SignalsHeld() { pthread_sigmask(SIG_SETMASK, &previous_, nullptr); }

WriteWindow::WriteWindow() {
    gWriting.fetch_add(1);
    open_ = !gEnding.load();  // seq_cst both here and in waitForWrites: one of the two sees the other
}

WriteWindow::~WriteWindow() { gWriting.fetch_sub(1); }

InterruptPoints::InterruptPoints() { gPolling = 1; }

InterruptPoints::~InterruptPoints() {
    gPolling = 0;
    if (gNoted != 0 && !taken_) stopNow(gNoted);
}

int InterruptPoints::arrived() {
    const int signal = gNoted;
    if (signal != 0) taken_ = true;
    return signal;
}

int notedSignal() { return gNoted; }

void raiseNotedSignal() {
    if (gNoted == 0) return;
    std::fflush(nullptr);  // what the command printed to stdout, before the process ends
    endBySignal(gNoted);
}

const char* signalName(int signal) {
    switch (signal) {
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
        case SIGHUP:
            return "SIGHUP";
        default:
            return "a signal";
    }
}

std::string interruptedAfter(int signal, int framesDone, int frameCount) {
    return std::string("interrupted by ") + signalName(signal) + " after " + std::to_string(framesDone) + " of " +
           std::to_string(frameCount) + (frameCount == 1 ? " frame" : " frames");
}

}  // namespace frugal
