// The frugal binary run in the background by a test, to be stopped by a signal midway (the fault
// and batch suites). Header-only, as CliSupport.h.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "TestSupport.h"

namespace frugal::test {

namespace fs = std::filesystem;

// The frugal binary in the background, working in `dir`/work (where its files go), its stdout and
// stderr in `dir`. It gets SIGINT, SIGTERM and SIGHUP as a terminal's foreground job has them,
// whatever this test process inherited (nohup, a background job).
class Background {
public:
    Background(const fs::path& dir, const std::vector<std::string>& args) : dir_(dir) {
        fs::create_directories(work());
        std::vector<std::string> argv = {binaryFor(args)};
        argv.insert(argv.end(), args.begin(), args.end());
        std::vector<char*> pointers;
        for (std::string& a : argv) pointers.push_back(a.data());
        pointers.push_back(nullptr);
        const std::string workDir = work().string(), out = (dir / "stdout.txt").string(),
                          err = (dir / "stderr.txt").string();
        pid_ = fork();
        if (pid_ == 0) {
            const int outFd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            const int errFd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
            if (outFd < 0 || errFd < 0 || dup2(outFd, 1) < 0 || dup2(errFd, 2) < 0 || chdir(workDir.c_str()) != 0)
                _exit(126);
            sigset_t none;
            sigemptyset(&none);
            sigprocmask(SIG_SETMASK, &none, nullptr);
            for (int handled : {SIGINT, SIGTERM, SIGHUP}) signal(handled, SIG_DFL);
            execv(pointers[0], pointers.data());
            _exit(127);
        }
    }
    ~Background() {
        if (status_ < 0 && pid_ > 0) {
            kill(pid_, SIGKILL);
            wait();
        }
    }
    Background(const Background&) = delete;
    Background& operator=(const Background&) = delete;

    fs::path work() const { return dir_ / "work"; }
    std::string err() const { return readAll(dir_ / "stderr.txt"); }
    void send(int signal) const { kill(pid_, signal); }

    // Waits until `ready` holds (true) or the process has ended (false); a minute at most, so that
    // a broken build fails the test instead of hanging it.
    bool waitUntil(const std::function<bool()>& ready) {
        for (int polls = 0; polls < 30000; ++polls) {
            if (ready()) return true;
            int raw = 0;
            if (waitpid(pid_, &raw, WNOHANG) == pid_) {
                status_ = decode(raw);
                return ready();
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
        return false;
    }

    // The exit status, or 128 + the signal that ended it.
    int wait() {
        if (status_ < 0) {
            int raw = 0;
            if (waitpid(pid_, &raw, 0) == pid_) status_ = decode(raw);
        }
        return status_;
    }

private:
    static int decode(int raw) { return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw); }

    fs::path dir_;
    pid_t pid_ = -1;
    int status_ = -1;
};

}  // namespace frugal::test
