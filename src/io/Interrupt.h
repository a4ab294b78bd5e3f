// SIGINT, SIGTERM and SIGHUP in the middle of a command: the files already written stay whole, no
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

namespace frugal {

// Handles SIGINT, SIGTERM and SIGHUP as above (the command line's main calls it first, on its
// main thread, before any other thread exists). A signal the process was started with ignored
// (a background job's SIGINT, nohup's SIGHUP) stays ignored. SIGXFSZ is ignored too, so that a file
// growing past `ulimit -f` fails its write (EFBIG: one error line) instead of dumping core. Without
// this call (a program that uses frugal as a library) the signals keep their own handling and
// InterruptPoints never sees one; SignalsHeld still keeps a write whole.
void installInterruptHandler();

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

// A stretch of work on the main thread that stops at points of its own choosing: while one lives, a
// signal is only noted. One at a time.
class InterruptPoints {
public:
    InterruptPoints();
    // A signal that came and was not taken through arrived() stops the process now, as outside.
    ~InterruptPoints();
    InterruptPoints(const InterruptPoints&) = delete;
    InterruptPoints& operator=(const InterruptPoints&) = delete;

    // The signal that came since this began, or 0. A non-zero answer is the caller's to report (one
    // line: what it finished) before it returns; main re-raises the signal after the command.
    int arrived();

private:
    bool taken_ = false;
};

// The signal an InterruptPoints noted and took (a command stopped by it), or 0: a caller that runs
// commands one after another (frugal batch) stops there; main then ends the process by it.
int notedSignal();

// Called by main once the command has returned: a signal an InterruptPoints took ends the process
// now, by that signal's default action. Returns when there was none.
void raiseNotedSignal();

// "SIGINT", "SIGTERM", "SIGHUP", or "a signal".
const char* signalName(int signal);

// What a sequence says when it stops for `signal`: "interrupted by SIGTERM after 3 of 10 frames".
std::string interruptedAfter(int signal, int framesDone, int frameCount);

}  // namespace frugal
