// FrameWriter (frugal/Files.h): frames' files encoded and written on threads of their own.
//
// A frame given to write() becomes a job of one task per file (colour, depth, ids), so that even a
// single frame's files are encoded side by side. The thread that finishes a job's last file commits
// it, and every job after it whose files are ready, in the order given: one thread commits at a
// time (`committing`), so the files on disk are always those of a prefix of the frames, and two
// frames naming the same file end as if written one after the other. The caller takes a finished
// job off the front of the queue to reuse its images' memory for the next frame.
//
// Signals: the worker threads block SIGINT, SIGTERM and SIGHUP for their whole life, so a signal
// goes to the main thread (io/Interrupt.h); OutputSet::commit holds a WriteWindow, so a handler
// that ends the process at once first waits for the temporary files being written to be renamed
// or removed.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <new>
#include <optional>
#include <system_error>
#include <thread>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "io/ImageIO.h"
#include "io/Interrupt.h"

namespace frugal {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

enum class Plane : std::uint8_t { Color, Depth, Ids, Linear };

struct Job {
    std::size_t index = 0;
    Frame frame;
    std::vector<std::pair<std::string, Plane>> files;  // in writeFrame's order: colour, depth, ids, linear
    std::vector<std::optional<Result<Content>>> encoded;
    int remaining = 0;   // files not yet encoded
    bool ready = false;  // every file encoded
    bool done = false;   // committed, or skipped after an error
    bool wrote = false;  // committed
    double encodeMs = 0.0, writeMs = 0.0;
};

// The files `paths` names, in writeFrame's order: colour, depth, ids, linear (empty paths left out).
std::vector<std::pair<std::string, Plane>> filesOf(const FramePaths& paths) {
    std::vector<std::pair<std::string, Plane>> files;
    for (const auto& [path, plane] : {std::pair{&paths.color, Plane::Color},
                                      {&paths.depth, Plane::Depth},
                                      {&paths.ids, Plane::Ids},
                                      {&paths.linear, Plane::Linear}})
        if (!path->empty()) files.emplace_back(*path, plane);
    return files;
}

Result<Content> encodeFile(const std::string& path, Plane plane, const Frame& frame, int level) {
    switch (plane) {
        case Plane::Color:
            return encodeColorPng(frame.color, PngOptions::atLevel(level));
        case Plane::Depth:
            if (hasExtension(path, ".pfm")) return encodeDepthPfm(frame.depth);
            return encodeDepthPng(frame.depth, PngOptions::atLevel(level));
        case Plane::Ids:
            return encodeIdPng(frame.ids, PngOptions::atLevel(level));
        case Plane::Linear:
            if (hasExtension(path, ".pfm")) return encodeLinearPfm(frame.linear);
            return encodeLinearPng(frame.linear, PngOptions::atLevel(level));
    }
    return Error{"unreachable"};
}

// A file asked of an image the frame does not hold: ids drawn without, depth not read back.
std::optional<Error> missingImage(const FramePaths& paths, const Frame& frame) {
    if (!paths.ids.empty() && frame.ids.ids.empty())
        return Error{"ids " + paths.ids + ": the frame has no ids (Settings::ids)"};
    if (!paths.depth.empty() && frame.depth.values.empty())
        return Error{"depth " + paths.depth + ": the frame has no depth (rendered with ReadBack{.depth = false})"};
    if (!paths.linear.empty() && frame.linear.rgba.empty())
        return Error{"linear " + paths.linear + ": the frame has no linear colour (Settings::linear)"};
    return std::nullopt;
}

int defaultThreads() {
    static const int cores = int(std::clamp(std::thread::hardware_concurrency(), 1u, 4u));
    return cores;
}

}  // namespace

struct FrameWriter::Impl {
    Options options;
    std::mutex mutex;
    std::condition_variable work;                    // a task to do, or stopping
    std::condition_variable moved;                   // a job done
    std::deque<std::unique_ptr<Job>> jobs;           // given and not yet taken off, in order
    std::deque<std::pair<Job*, std::size_t>> tasks;  // (job, file) to encode
    std::vector<Frame> spare;                        // finished frames' memory
    std::vector<Written> written;
    std::optional<Error> error;
    std::size_t given = 0;
    bool committing = false, stopping = false;
    std::vector<std::thread> threads;

    explicit Impl(const Options& o) : options(o) {
        try {
            for (int i = 0; i < options.threads; ++i) threads.emplace_back([this] { run(); });
        } catch (...) {  // the threads started stop before the error leaves
            stop();
            throw;
        }
    }

    ~Impl() { stop(); }

    // Waits for every job given, then ends the threads.
    void stop() {
        {
            std::unique_lock lock(mutex);
            moved.wait(lock, [&] { return allDone(); });
            stopping = true;
        }
        work.notify_all();
        for (std::thread& t : threads) t.join();
    }

    bool allDone() const {
        return std::all_of(jobs.begin(), jobs.end(), [](const std::unique_ptr<Job>& j) { return j->done; });
    }

    void run() {
        const SignalsHeld held;  // for this thread's whole life: signals go to the main thread
        std::unique_lock lock(mutex);
        for (;;) {
            work.wait(lock, [&] { return stopping || !tasks.empty(); });
            if (tasks.empty()) return;
            const auto [job, file] = tasks.front();
            tasks.pop_front();
            const bool skip = error.has_value();
            lock.unlock();
            const auto start = Clock::now();
            if (!skip) job->encoded[file] = encodeSafely(*job, file);
            const double ms = msSince(start);
            lock.lock();
            job->encodeMs += ms;
            if (--job->remaining == 0) {
                job->ready = true;
                commitReady(lock);
            }
        }
    }

    Result<Content> encodeSafely(const Job& job, std::size_t file) const {
        const auto& [path, plane] = job.files[file];
        try {
            return encodeFile(path, plane, job.frame, options.pngLevel);
        } catch (const std::bad_alloc&) {
            return Error{"out of memory while encoding it", ErrorKind::OutOfMemory};
        } catch (const std::exception& e) {  // nothing else is thrown; a thread must not end by one
            return Error{std::string("cannot encode it: ") + e.what()};
        }
    }

    // Commits the first jobs not done while their files are ready, one thread at a time, in order.
    void commitReady(std::unique_lock<std::mutex>& lock) {
        if (committing) return;  // that thread will see this job too: it looks again under the lock
        committing = true;
        for (;;) {
            const auto next = std::find_if(jobs.begin(), jobs.end(), [](const auto& j) { return !j->done; });
            if (next == jobs.end() || !(*next)->ready) break;
            Job& job = **next;
            const bool skip = error.has_value();
            lock.unlock();
            const auto start = Clock::now();
            Result<bool> committed = true;
            if (!skip) {
                OutputSet set;
                for (std::size_t k = 0; k < job.files.size(); ++k)
                    set.add(job.files[k].first, std::move(*job.encoded[k]));
                committed = set.commit();
            }
            job.encoded.clear();
            const double ms = msSince(start);
            lock.lock();
            job.writeMs = ms;
            job.done = true;
            job.wrote = !skip && committed;
            if (!committed && !error) error = committed.error();
            moved.notify_all();
        }
        committing = false;
    }

    // Takes the finished jobs off the front: their records, and their frames' memory as spare.
    void takeDone() {
        while (!jobs.empty() && jobs.front()->done) {
            Job& job = *jobs.front();
            if (job.wrote) written.push_back({job.index, job.encodeMs, job.writeMs});
            if (spare.size() < 2) spare.push_back(std::move(job.frame));
            jobs.pop_front();
        }
    }
};

Result<FrameWriter> FrameWriter::create(const Options& options) {
    Options o = options;
    if (o.pngLevel != kAutoPngLevel && (o.pngLevel < 0 || o.pngLevel > kMaxPngLevel))
        return Error{"png-level " + std::to_string(o.pngLevel) + ": must be 0 (fastest, largest) to " +
                         std::to_string(kMaxPngLevel) + " (smallest, slowest), or auto (" +
                         std::to_string(kAutoPngLevel) + ")",
                     ErrorKind::BadInput, true};
    if (o.threads < 0 || o.threads > 64)
        return Error{"writer threads " + std::to_string(o.threads) + ": must be 1 to 64, or 0 for one per core"};
    if (o.queue < 0 || o.queue > 1024)
        return Error{"writer queue " + std::to_string(o.queue) + ": must be 1 to 1024 frames, or 0 for threads + 1"};
    if (o.threads == 0) o.threads = defaultThreads();
    if (o.queue == 0) o.queue = o.threads + 1;
    try {
        return FrameWriter(std::make_unique<Impl>(o));
    } catch (const std::system_error& e) {  // no thread could be started (ulimit -u, a container's pids limit)
        return Error{"writer threads " + std::to_string(o.threads) + ": cannot start them: " + e.what(),
                     ErrorKind::Io};
    }
}

FrameWriter::FrameWriter() : FrameWriter(std::move(*create({}))) {}
FrameWriter::FrameWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FrameWriter::FrameWriter(FrameWriter&& other) noexcept = default;
FrameWriter& FrameWriter::operator=(FrameWriter&& other) noexcept = default;
FrameWriter::~FrameWriter() = default;

int FrameWriter::threads() const { return impl_->options.threads; }

Result<bool> FrameWriter::write(const FramePaths& paths, Frame& frame) {
    if (std::optional<Error> missing = missingImage(paths, frame)) return *missing;
    Impl& w = *impl_;
    auto job = std::make_unique<Job>();
    job->files = filesOf(paths);
    job->encoded.resize(job->files.size());
    job->remaining = int(job->files.size());

    std::unique_lock lock(w.mutex);
    for (;;) {
        w.takeDone();
        if (w.error) return *w.error;
        if (int(w.jobs.size()) < w.options.queue) break;
        w.moved.wait(lock);
    }
    job->index = w.given++;
    job->frame = std::move(frame);
    frame = Frame{};
    if (!w.spare.empty()) {
        frame = std::move(w.spare.back());
        w.spare.pop_back();
    }
    Job* added = job.get();
    w.jobs.push_back(std::move(job));
    if (added->files.empty()) {  // nothing to write: done in turn
        added->ready = true;
        w.commitReady(lock);
        return true;
    }
    for (std::size_t k = 0; k < added->files.size(); ++k) w.tasks.emplace_back(added, k);
    lock.unlock();
    w.work.notify_all();
    return true;
}

Result<bool> FrameWriter::finish() {
    Impl& w = *impl_;
    std::unique_lock lock(w.mutex);
    w.moved.wait(lock, [&] { return w.allDone(); });
    w.takeDone();
    if (w.error) return *w.error;
    return true;
}

std::vector<FrameWriter::Written> FrameWriter::takeWritten() {
    Impl& w = *impl_;
    std::lock_guard lock(w.mutex);
    w.takeDone();
    return std::exchange(w.written, {});
}

Result<bool> writeFrame(const FramePaths& paths, const Frame& frame, int pngLevel) {
    if (std::optional<Error> missing = missingImage(paths, frame)) return *missing;
    OutputSet files;
    for (const auto& [path, plane] : filesOf(paths)) files.add(path, encodeFile(path, plane, frame, pngLevel));
    return files.commit();
}

}  // namespace frugal
