// The library's side of interruption (frugal/Interrupt.h says what a program sees): files written
// with the signals held, so that a temporary file exists only while no handler can run, and the
// write windows a handler waits for before it ends the process.
//
// SIGINT, SIGTERM and SIGHUP in the middle of a command, in detail: the files already written stay whole, no
// temporary file is left, one line says what happened, and the process still ends by the signal,
// so that the shell, make or a script's loop sees an interrupted run (exit status 128 + signal).
//
// Why it is safe at any instant (signal-safety(7)):
// - the files are written with the signals blocked on the writing thread (SignalsHeld, taken by
//   OutputSet::commit for its temporary files and renames), so a temporary file exists only while
//   no handler can run on that thread, and a set of files is never half renamed; a write on another
//   thread (FrameWriter) holds a WriteWindow, which the handler waits for before it ends the process;
// - the handler acts only on the main thread, the one that writes: a signal the kernel hands to
//   another thread (llvmpipe's, the software backend's pool) is passed on with pthread_kill, and
//   waits there while a write holds it;
// - in the handler only async-signal-safe calls are made: write(2) of a fixed line, sigaction,
//   pthread_sigmask and raise.
// Outside a stretch of work that polls (InterruptPoints) the handler writes
// "error: interrupted by SIGTERM" and ends the process by the signal at once. Inside one it only
// notes the signal; the work stops at its next point (between two frames), says what it finished,
// and the command returns; main then ends the process by the signal (raiseNotedSignal). A second
// signal while the first waits for a point stops at once. SIGKILL cannot be caught; it too leaves
// only whole files, and at most one temporary file of the write it cut.
#pragma once

#include <csignal>
#include <string>

#include <frugal/Interrupt.h>

namespace frugal {

// While one lives, SIGINT, SIGTERM and SIGHUP are blocked on this thread (a signal that arrives
// waits, and is handled when the last one ends). A child started meanwhile inherits the block.
class SignalsHeld {
public:
    SignalsHeld();
    ~SignalsHeld();
    SignalsHeld(const SignalsHeld&) = delete;
    SignalsHeld& operator=(const SignalsHeld&) = delete;

private:
    sigset_t previous_;
};

// OutputSet::commit's temporary files on any thread (FrameWriter's write on threads of their own):
// while one lives, a handler that ends the process at once (stopNow: a second signal, or one outside
// InterruptPoints) waits for it to end, at most two seconds, so that the files it writes are renamed
// or removed first. Once the process is ending no new one opens (open() false: write nothing).
class WriteWindow {
public:
    WriteWindow();
    ~WriteWindow();
    WriteWindow(const WriteWindow&) = delete;
    WriteWindow& operator=(const WriteWindow&) = delete;
    bool open() const { return open_; }

private:
    bool open_ = false;
};

}  // namespace frugal
