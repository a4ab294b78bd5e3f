// SIGINT, SIGTERM and SIGHUP in the middle of a long run (a sequence, a report): the files already
// written stay whole, no temporary file is left, the run stops between two frames and says what it
// finished, and the process still ends by the signal, so that the shell, make or a script's loop
// sees an interrupted run (exit status 128 + signal). The frugal command line works so; a program of
// its own gets the same with these calls:
//
//   int main() {
//       frugal::installInterruptHandler();           // first, before any thread starts
//       {
//           frugal::InterruptPoints points;          // between frames, a signal is only noted
//           for (int i = 0; i < 1000; ++i) {
//               if (const int signal = points.arrived()) {
//                   std::fprintf(stderr, "error: %s\n", frugal::interruptedAfter(signal, i, 1000).c_str());
//                   break;
//               }
//               ...  // render frame i, write its files
//           }
//       }
//       frugal::raiseNotedSignal();                   // ends the process by the signal, if one came
//   }
//
// Files frugal writes are written with the signals held, and the handler waits for a write on
// another thread (FrameWriter's) to end: a signal at any instant leaves only whole files. Outside
// InterruptPoints the handler writes "error: interrupted by SIGTERM" and ends the process at once.
// A second signal while the first waits for a point stops at once. SIGKILL cannot be caught; it too
// leaves only whole files, and at most one temporary file of the write it cut.
#pragma once

#include <string>

namespace frugal {

// Handles SIGINT, SIGTERM and SIGHUP as above; call it first, on the main thread, before any other
// thread exists. A signal the process was started with ignored (a background job's SIGINT, nohup's
// SIGHUP) stays ignored. SIGXFSZ is ignored too, so that a file growing past `ulimit -f` fails its
// write (EFBIG: one error line) instead of dumping core. Without this call the signals keep their
// own handling and InterruptPoints never sees one; frugal's writes still leave only whole files.
void installInterruptHandler();

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
