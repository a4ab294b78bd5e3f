// Faults, end to end on the real binary (issue 11): SIGINT and SIGTERM in the middle of a command,
// a full device, a file-size limit, a folder that takes no file, a frame larger than the memory
// allowed, no EGL or a broken Mesa set-up, a GALLIUM_DRIVER that OSMesa or EGL cannot survive, and
// two processes rendering into one folder. Each ends with its one error line and exit status,
// nothing half written, nothing finished lost, and no temporary file left.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "BackgroundSupport.h"
#include "JsonSupport.h"
#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

using test::Background;
using test::CliRun;
using test::filesIn;
using test::readAll;
using test::runFrugal;

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;  // the sanitizers reserve terabytes of address space: no `ulimit -v`
#else
constexpr bool kSanitized = false;
#endif

bool isLeftover(const std::string& name) {
    return name.find(".tmp-") != std::string::npos || name.find(".old-") != std::string::npos;
}

std::string frameName(const char* prefix, int frame) {
    char name[64];
    std::snprintf(name, sizeof name, "%s_%04d.png", prefix, frame);
    return name;
}

// The frames `frugal render --frames 0:99999` had written when `signal` reached it, at a random
// moment after its first frame, `tries` times: the process ends by the signal with one line saying
// how many frames it finished, those are exactly the files there, whole, and nothing else is.
void expectSequencesStopCleanly(const std::string& name, const std::string& backend, int signal, int tries) {
    std::mt19937 random(11);
    const std::regex line("error: interrupted by " + std::string(signal == SIGINT ? "SIGINT" : "SIGTERM") +
                          " after ([0-9]+) of 100000 frames");
    for (int t = 0; t < tries; ++t) {
        const int delayUs = std::uniform_int_distribution<int>(0, 15000)(random);
        SCOPED_TRACE("try " + std::to_string(t) + ", signal " + std::to_string(delayUs) + " us after the first frame");
        Background run(test::freshDir(name), {"render", "builtin:cubes", "--frames", "0:99999", "--size", "160x120",
                                              "-o", "f_%04d.png", "-q", "--backend", backend});
        ASSERT_TRUE(run.waitUntil([&run] { return fs::exists(run.work() / "f_0000.png"); })) << run.err();
        std::this_thread::sleep_for(std::chrono::microseconds(delayUs));
        run.send(signal);
        EXPECT_EQ(run.wait(), 128 + signal) << "ends by the signal, as the shell expects";
        for (const std::string& file : filesIn(run.work())) EXPECT_FALSE(isLeftover(file)) << file;
        const std::vector<std::string> errLines = test::lines(run.err());
        std::smatch match;
        if (errLines.size() != 1 || !std::regex_match(errLines[0], match, line)) {
            ADD_FAILURE() << "one line saying how many frames were finished, got: " << run.err();
            continue;
        }
        const int finished = std::stoi(match[1].str());
        std::vector<std::string> expected;
        for (int frame = 0; frame < finished; ++frame) expected.push_back(frameName("f", frame));
        EXPECT_EQ(filesIn(run.work()), expected) << "the finished frames, and no temporary file";
        for (const std::string& file : filesIn(run.work())) {
            Result<DecodedImage> image = readPng((run.work() / file).string());
            ASSERT_TRUE(image) << image.error().message;
            EXPECT_EQ(image->width * 1000 + image->height, 160120) << file;
        }
    }
}

// The issue's case: today a SIGTERM during a 160×120 sequence leaves f_NNNN.png.tmp-PID behind in
// about half the tries (the software backend spends most of a frame writing it).
TEST(FaultCliTest, SigtermMidSequenceKeepsTheFinishedFramesAndNoTemporaryFile) {
    expectSequencesStopCleanly("FaultSigtermSoftware", "software", SIGTERM, 24);
}

TEST(FaultCliTest, SigintMidSequenceOnGlKeepsTheFinishedFramesAndNoTemporaryFile) {
    expectSequencesStopCleanly("FaultSigintGl", "auto", SIGINT, 8);
}

// A second signal while the first waits for the frames queued to be written ends the process at
// once: whatever the writer's threads were writing is renamed or removed first (WriteWindow), so
// the files are still a prefix of the frames, each whole, and no temporary file is left. Slow
// files (640x480 colour and ids at level 9) keep frames queued when the signals come.
TEST(FaultCliTest, ASecondSignalWhileFramesAreWrittenLeavesWholeFilesOnly) {
    std::mt19937 random(5);
    for (int t = 0; t < 6; ++t) {
        const int gapUs = std::uniform_int_distribution<int>(0, 20000)(random);
        SCOPED_TRACE("try " + std::to_string(t) + ", " + std::to_string(gapUs) + " us between the signals");
        Background run(test::freshDir("FaultSecondSignal"),
                       {"render", "builtin:cubes", "--frames", "0:99999", "--size", "640x480", "--png-level", "9",
                        "-o", "f_%04d.png", "--ids", "i_%04d.png", "-q", "--backend", "software"});
        ASSERT_TRUE(run.waitUntil([&run] { return fs::exists(run.work() / "f_0001.png"); })) << run.err();
        run.send(SIGTERM);
        std::this_thread::sleep_for(std::chrono::microseconds(gapUs));
        run.send(SIGTERM);
        EXPECT_EQ(run.wait(), 128 + SIGTERM);
        const std::vector<std::string> files = filesIn(run.work());
        for (const std::string& file : files) EXPECT_FALSE(isLeftover(file)) << file;
        const std::size_t frames = files.size() / 2;
        std::vector<std::string> expected;
        for (int frame = 0; frame < int(frames); ++frame) expected.push_back(frameName("f", frame));
        for (int frame = 0; frame < int(frames); ++frame) expected.push_back(frameName("i", frame));
        EXPECT_EQ(files, expected) << "whole sets of a prefix of the frames";
        for (const std::string& file : files) {
            Result<DecodedImage> image = readPng((run.work() / file).string());
            ASSERT_TRUE(image) << file << ": " << image.error().message;
            EXPECT_EQ(image->width * 1000 + image->height, 640480) << file;
        }
    }
}

TEST(FaultCliTest, SigtermMidDiffSequenceKeepsWholeImageSets) {
    std::mt19937 random(12);
    const std::regex line("error: interrupted by SIGTERM after ([0-9]+) of 100000 frames");
    for (int t = 0; t < 6; ++t) {
        SCOPED_TRACE("try " + std::to_string(t));
        Background run(test::freshDir("FaultSigtermDiff"),
                       {"diff", "builtin:cubes", "--frames", "0:99999", "--size", "96x72", "--out", "images", "-q"});
        ASSERT_TRUE(run.waitUntil([&run] { return fs::exists(run.work() / "images" / "mask_0000.png"); })) << run.err();
        std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 20000)(random)));
        run.send(SIGTERM);
        EXPECT_EQ(run.wait(), 128 + SIGTERM);
        const std::vector<std::string> errLines = test::lines(run.err());
        std::smatch match;
        ASSERT_TRUE(errLines.size() == 1 && std::regex_match(errLines[0], match, line)) << run.err();
        const int finished = std::stoi(match[1].str());
        std::vector<std::string> expected;
        for (const char* kind : {"actual", "mask", "reference"})
            for (int frame = 0; frame < finished; ++frame) expected.push_back(frameName(kind, frame));
        std::sort(expected.begin(), expected.end());
        EXPECT_EQ(filesIn(run.work() / "images"), expected) << "every finished frame's three images, nothing else";
    }
}

// A report stopped at a random moment (loading, computing, writing, gnuplot drawing): it ends by the
// signal with "error: interrupted by SIGTERM" (or, before main, by the signal alone), or finished
// first; either way its files are all there and whole, or none is, and no temporary file is left.
TEST(FaultCliTest, SigtermDuringAReportLeavesAllItsFilesOrNone) {
    const bool plot = test::haveGnuplot();
    std::mt19937 random(13);
    // Each about half a second here, gnuplot included.
    const std::vector<std::vector<std::string>> commands = {{"state-sim", "--seeds", "1"},
                                                            {"span-bench", "--spans", "100", "--speed-ms", "0"}};
    for (const std::vector<std::string>& command : commands) {
        for (int t = 0; t < 10; ++t) {
            const int delayUs = std::uniform_int_distribution<int>(0, 800000)(random);
            SCOPED_TRACE(command[0] + ", signal " + std::to_string(delayUs) + " us after the start");
            std::vector<std::string> args = command;
            args.insert(args.end(), {"--json", "r.json", "--csv", "r.csv"});
            if (plot) args.insert(args.end(), {"--plot", "r.svg"});
            Background run(test::freshDir("FaultSigtermReport"), args);
            std::this_thread::sleep_for(std::chrono::microseconds(delayUs));
            run.send(SIGTERM);
            const int status = run.wait();
            if (status == 0) {
                EXPECT_EQ(run.err(), "");
            } else {
                EXPECT_EQ(status, 128 + SIGTERM) << run.err();
                EXPECT_TRUE(run.err().empty() || run.err() == "error: interrupted by SIGTERM\n") << run.err();
            }
            const std::vector<std::string> files = filesIn(run.work());
            for (const std::string& file : files) EXPECT_FALSE(isLeftover(file)) << file;
            const bool any = fs::exists(run.work() / "r.json") || fs::exists(run.work() / "r.csv");
            if (status == 0 || any) {  // the JSON and the CSV are one set (OutputSet)
                EXPECT_TRUE(fs::exists(run.work() / "r.json") && fs::exists(run.work() / "r.csv"))
                    << "the set is whole";
                EXPECT_FALSE(test::readJson(run.work() / "r.json").is_discarded());
                EXPECT_EQ(fs::exists(run.work() / "r.gp"), plot);
            }
            if (fs::exists(run.work() / "r.svg")) {
                const std::string svg = readAll(run.work() / "r.svg");
                EXPECT_NE(svg.find("</svg>"), std::string::npos) << "gnuplot finished the plot";
            }
        }
    }
}

// compare on two noisy 1024×1024 images, stopped at random moments: the mask and the JSON are
// written together or not at all.
TEST(FaultCliTest, SigtermDuringCompareLeavesTheMaskAndJsonTogetherOrNeither) {
    const fs::path images = test::freshDir("FaultSigtermCompareImages");
    std::mt19937 noise(5);
    for (const char* name : {"a.png", "b.png"}) {
        std::vector<std::uint8_t> rgba(std::size_t(1024) * 1024 * 4);
        for (std::uint8_t& byte : rgba) byte = std::uint8_t(noise());
        ASSERT_TRUE(writeFileAtomic((images / name).string(), encodePng(1024, 1024, 4, 8, rgba.data())));
    }
    std::mt19937 random(14);
    for (int t = 0; t < 8; ++t) {
        const int delayUs = std::uniform_int_distribution<int>(0, 600000)(random);
        SCOPED_TRACE("signal " + std::to_string(delayUs) + " us after the start");
        Background run(test::freshDir("FaultSigtermCompare"),
                       {"compare", (images / "a.png").string(), (images / "b.png").string(), "--mask", "m.png",
                        "--json", "c.json"});
        std::this_thread::sleep_for(std::chrono::microseconds(delayUs));
        run.send(SIGTERM);
        const int status = run.wait();
        EXPECT_TRUE(status == 1 || status == 128 + SIGTERM) << status << ": " << run.err();  // 1: the images differ
        const std::vector<std::string> files = filesIn(run.work());
        EXPECT_TRUE(files.empty() || files == (std::vector<std::string>{"c.json", "m.png"}))
            << testing::PrintToString(files);
        if (!files.empty()) {
            EXPECT_TRUE(readPng((run.work() / "m.png").string()));
            EXPECT_FALSE(test::readJson(run.work() / "c.json").is_discarded());
        }
    }
}

bool isCharacterDevice(const fs::path& path) {
    struct stat status {};
    return ::lstat(path.c_str(), &status) == 0 && S_ISCHR(status.st_mode);
}

TEST(FaultCliTest, OutputToAFullDeviceIsOneLineAndLeavesTheDeviceAndNoOtherFile) {
    const fs::path dir = test::freshDir("FaultFullDevice");
    const std::regex full("error: (.+): write failed after 0 of [0-9]+ bytes: No space left on device");
    std::smatch match;
    // /dev/full through a link here: a writer that renamed a file over it (before the fix, as root:
    // /dev/full became a JSON file) replaces the link, not the machine's device.
    fs::create_symlink("/dev/full", dir / "full.png");

    // The JSON comes after the frame, a finished file of its own, which stays.
    CliRun run = runFrugal(dir, {"render", "--size", "64x48", "--backend", "software", "-q", "--json", "full.png"});
    EXPECT_EQ(run.status, 1);
    std::vector<std::string> errLines = run.errLines();
    ASSERT_EQ(errLines.size(), 1u) << run.err;
    ASSERT_TRUE(std::regex_match(errLines[0], match, full)) << run.err;
    EXPECT_EQ(match[1].str(), "full.png");
    EXPECT_TRUE(fs::is_symlink(dir / "full.png")) << "written in place, never replaced by a file";
    EXPECT_TRUE(isCharacterDevice("/dev/full"));
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"frame.png", "full.png"}));
    EXPECT_TRUE(readPng((dir / "frame.png").string()));
    fs::remove(dir / "frame.png");

    // An image to the device: written in place, first, so the others of its set are not written.
    run = runFrugal(dir,
                    {"render", "--size", "64x48", "--backend", "software", "-q", "-o", "ok.png", "--ids", "full.png"});
    EXPECT_EQ(run.status, 1);
    errLines = run.errLines();
    ASSERT_EQ(errLines.size(), 1u) << run.err;
    ASSERT_TRUE(std::regex_match(errLines[0], match, full)) << run.err;
    EXPECT_EQ(match[1].str(), "full.png");
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"full.png"});
    EXPECT_TRUE(fs::is_symlink(dir / "full.png"));

    // A report's set likewise.
    run = runFrugal(dir, {"state-sim", "--seeds", "1", "--json", "full.png", "--csv", "s.csv"});
    EXPECT_EQ(run.status, 1);
    ASSERT_EQ(run.errLines().size(), 1u) << run.err;
    EXPECT_TRUE(std::regex_match(run.errLines()[0], full)) << run.err;
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"full.png"});
}

// `--json /dev/stdout` puts the JSON where stdout goes, here a file: through a link in the test's
// folder to /proc/self/fd/1, as /dev/stdout is (a writer that renamed over it would replace the
// link, not the machine's /dev/stdout).
TEST(FaultCliTest, AJsonThroughStdoutsLinkGoesToStdout) {
    const fs::path dir = test::freshDir("FaultStdout");
    fs::create_symlink("/proc/self/fd/1", dir / "stdout.json");
    const CliRun run =
        runFrugal(dir, {"render", "--size", "32x24", "--backend", "software", "-q", "--json", "stdout.json"});
    EXPECT_EQ(run.status, 0) << run.err;
    const nlohmann::json meta = nlohmann::json::parse(run.out, nullptr, /*allow_exceptions=*/false);
    ASSERT_FALSE(meta.is_discarded()) << run.out;
    EXPECT_EQ(meta["backend"], "software");
    EXPECT_TRUE(fs::is_symlink(dir / "stdout.json"));
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"frame.png", "stdout.json"}));
}

// `ulimit -f` (a full disk's near relative that any user can set): the write fails with EFBIG
// instead of SIGXFSZ's core dump, and the set is not written.
TEST(FaultCliTest, AFileSizeLimitIsOneLineAndNoFile) {
    const fs::path dir = test::freshDir("FaultFileSize");
    const CliRun run =
        runFrugal(dir, {"render", "--size", "320x240", "--backend", "software", "-q", "-o", "c.png", "--ids", "i.png"},
                  "ulimit -f 4 &&");  // blocks of 512 bytes in dash, 1024 in bash
    EXPECT_EQ(run.status, 1);
    ASSERT_EQ(run.errLines().size(), 1u) << run.err;
    EXPECT_TRUE(std::regex_match(
        run.errLines()[0], std::regex("error: [ci].png: write failed after [0-9]+ of [0-9]+ bytes: File too large")))
        << run.err;
    EXPECT_TRUE(filesIn(dir).empty());
}

TEST(FaultCliTest, AFolderThatTakesNoFileIsOneLineAndLeavesNoFileOfTheSet) {
    const fs::path dir = test::freshDir("FaultFolder");
    test::writeFile(dir / "file.txt", "a regular file");
    CliRun run = runFrugal(dir, {"render", "--size", "64x48", "--backend", "software", "-q", "-o", "ok.png", "--depth",
                                 "file.txt/depth.png"});
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.err, "error: file.txt/depth.png: cannot write: Not a directory\n");
    EXPECT_EQ(filesIn(dir), std::vector<std::string>{"file.txt"});

    // A read-only folder; root writes through permission bits, so there the folder is sysfs's.
    const fs::path readOnly = dir / "read-only";
    fs::create_directory(readOnly);
    fs::permissions(readOnly, fs::perms::owner_read | fs::perms::owner_exec);
    const bool bitsStopWrites = access(readOnly.c_str(), W_OK) != 0;
    const std::string target = bitsStopWrites ? "read-only/x.png" : "/sys/frugal-fault-test.png";
    if (!bitsStopWrites && !fs::is_directory("/sys/kernel")) {
        fs::permissions(readOnly, fs::perms::owner_all);
        GTEST_SKIP() << "running as root with no sysfs: no folder here refuses a file";
    }
    run = runFrugal(dir, {"render", "--size", "64x48", "--backend", "software", "-q", "-o", "ok.png", "--ids", target});
    fs::permissions(readOnly, fs::perms::owner_all);
    EXPECT_EQ(run.status, 1);
    EXPECT_EQ(run.err, "error: " + target + ": cannot write: Permission denied\n");
    EXPECT_EQ(filesIn(dir), (std::vector<std::string>{"file.txt", "read-only"}));
    EXPECT_TRUE(fs::is_empty(readOnly));
}

TEST(FaultCliTest, ATargetLargerThanABackendTakesIsRefusedWithTheLimit) {
    const fs::path dir = test::freshDir("FaultHugeTarget");
    for (const char* backend : {"software", "egl", "osmesa"}) {
        SCOPED_TRACE(backend);
        const CliRun run = runFrugal(dir, {"render", "--size", "60000x60000", "--backend", backend, "-q"});
        if (run.status == 3) continue;  // the backend is not here: its one line is tested elsewhere
        EXPECT_EQ(run.status, 1);
        ASSERT_EQ(run.errLines().size(), 1u) << run.err;
        EXPECT_TRUE(std::regex_match(run.errLines()[0],
                                     std::regex("error: --size 60000x60000: [a-z-]+ cannot create a target that large "
                                                "\\(at most [0-9]+ pixels a side\\)")))
            << run.err;
        EXPECT_TRUE(filesIn(dir).empty());
    }
}

// A size the backend takes but `ulimit -v` does not hold: refused before anything is allocated,
// with the bytes needed and left, on every backend (the run without the check ends in
// std::bad_alloc's abort when the frame is read back).
TEST(FaultCliTest, AFrameLargerThanMemoryAllowsIsRefusedUpFront) {
    if (kSanitized) GTEST_SKIP() << "a sanitizer's shadow memory does not fit under ulimit -v";
    const fs::path dir = test::freshDir("FaultMemory");
    const std::regex refused(
        "error: --size 16384x16384: needs about 9\\.7 GB \\(36 bytes a pixel: target, read-back, PNG encoding\\), "
        "more than the [0-9]+\\.[0-9] GB left \\(ulimit -v\\)");
    for (const char* backend : {"software", "egl", "osmesa"}) {
        SCOPED_TRACE(backend);
        const CliRun run =
            runFrugal(dir, {"render", "--size", "16384x16384", "--backend", backend, "-q"}, "ulimit -v 4000000 &&");
        if (run.status == 3) continue;
        EXPECT_EQ(run.status, 1);
        ASSERT_EQ(run.errLines().size(), 1u) << run.err;
        EXPECT_TRUE(std::regex_match(run.errLines()[0], refused)) << run.err;
        EXPECT_TRUE(filesIn(dir).empty());
    }
}

// --reuse makes a second target of the frame's size: a limit that holds the frame but not the pair
// as well is refused before the pair is made (before, the first frame's read-back failed).
TEST(FaultCliTest, AStaticPairLargerThanMemoryAllowsIsRefusedUpFront) {
    if (kSanitized) GTEST_SKIP() << "a sanitizer's shadow memory does not fit under ulimit -v";
    const fs::path dir = test::freshDir("FaultMemoryReuse");
    // 12000x12000: the frame needs 5.2 GB, its target 1.7 of them; the pair and the rest 5.2 GB more.
    const CliRun run =
        runFrugal(dir, {"render", "builtin:cubes", "--reuse", "--size", "12000x12000", "--backend", "software", "-q"},
                  "ulimit -v 6200000 &&");
    EXPECT_EQ(run.status, 1);
    ASSERT_EQ(run.errLines().size(), 1u) << run.err;
    EXPECT_TRUE(std::regex_match(
        run.errLines()[0], std::regex("error: --reuse: 12000x12000 needs about 5\\.2 GB more \\(a static pair of 12 "
                                      "bytes a pixel, then the frame's read-back and PNG encoding\\), more than "
                                      "the [0-9]\\.[0-9] GB left \\(ulimit -v\\)")))
        << run.err;
    EXPECT_TRUE(filesIn(dir).empty());
}

// A memory cgroup made for one test under this process's own (a container's limit, as `docker run
// --memory` sets it): v1 (memory.limit_in_bytes) or v2 (memory.max). Making one needs root and a
// writable cgroup file system; where that fails, `dir()` is empty and `why()` says what failed.
class MemoryCgroup {
public:
    explicit MemoryCgroup(std::uint64_t limit) {
        std::ifstream in("/proc/self/cgroup");
        for (std::string line; std::getline(in, line);) {
            // "0::/path" (v2) or "4:memory:/path" (v1, controllers separated by commas).
            const std::size_t first = line.find(':'), second = line.find(':', first + 1);
            if (first == std::string::npos || second == std::string::npos) continue;
            const std::string controllers = "," + line.substr(first + 1, second - first - 1) + ",";
            const bool v2 = controllers == ",,";
            if (!v2 && controllers.find(",memory,") == std::string::npos) continue;
            const fs::path parent = fs::path(v2 ? "/sys/fs/cgroup" : "/sys/fs/cgroup/memory") /
                                    fs::path(line.substr(second + 1)).relative_path();
            const fs::path dir = parent / ("frugal-test-" + std::to_string(getpid()));
            const char* limitFile = v2 ? "memory.max" : "memory.limit_in_bytes";
            std::error_code ec;
            if (!fs::create_directory(dir, ec)) {
                why_ += dir.string() + ": " + (ec ? ec.message() : "exists") + "; ";
                continue;
            }
            // A folder the kernel did not fill (a tmpfs where no cgroup v2 is mounted) is no cgroup.
            if (!fs::exists(dir / "cgroup.procs") || !fs::exists(dir / limitFile)) {
                why_ += dir.string() + ": no " + limitFile + " (no memory controller there); ";
                fs::remove_all(dir, ec);
                continue;
            }
            std::ofstream(dir / limitFile) << limit;
            std::uint64_t set = 0;
            std::ifstream(dir / limitFile) >> set;
            if (set != limit) {
                why_ += dir.string() + ": " + limitFile + " did not take " + std::to_string(limit) + "; ";
                ::rmdir(dir.c_str());
                continue;
            }
            // A process must be able to join it (a sandbox may refuse: EPERM, EBUSY).
            const std::string join = "sh -c 'echo $$ > " + (dir / "cgroup.procs").string() + "' 2>/dev/null";
            if (std::system(join.c_str()) != 0) {
                why_ += dir.string() + ": a process cannot join it; ";
                ::rmdir(dir.c_str());
                continue;
            }
            dir_ = dir;
            return;
        }
        if (why_.empty()) why_ = "no memory cgroup in /proc/self/cgroup";
    }
    ~MemoryCgroup() {
        if (!dir_.empty()) ::rmdir(dir_.c_str());  // its processes have ended: runFrugal waits for them
    }
    MemoryCgroup(const MemoryCgroup&) = delete;
    MemoryCgroup& operator=(const MemoryCgroup&) = delete;

    const fs::path& dir() const { return dir_; }
    const std::string& why() const { return why_; }

private:
    fs::path dir_;
    std::string why_;
};

// The same under a cgroup's limit, in a cgroup made for the test: the message names the cgroup.
// Nothing reserves terabytes in a cgroup (it counts pages used), so this holds under the sanitizers.
TEST(FaultCliTest, AFrameLargerThanACgroupAllowsIsRefusedUpFront) {
    const MemoryCgroup cgroup(std::uint64_t(256) << 20);
    if (cgroup.dir().empty()) GTEST_SKIP() << "cannot make a memory cgroup here: " << cgroup.why();
    const fs::path dir = test::freshDir("FaultCgroup");
    const std::regex refused(
        "error: --size 8192x8192: needs about 2\\.4 GB \\(36 bytes a pixel: target, read-back, PNG encoding\\), "
        "more than the 0\\.[0-3] GB left \\(cgroup " +
        cgroup.dir().string() + " memory\\.(max|limit_in_bytes)\\)");
    for (const char* backend : {"software", "egl"}) {
        SCOPED_TRACE(backend);
        const CliRun run = runFrugal(dir, {"render", "--size", "8192x8192", "--backend", backend, "-q"},
                                     "echo $$ > " + (cgroup.dir() / "cgroup.procs").string() + " &&");
        if (run.status == 3) continue;
        EXPECT_EQ(run.status, 1);
        ASSERT_EQ(run.errLines().size(), 1u) << run.err;
        EXPECT_TRUE(std::regex_match(run.errLines()[0], refused)) << run.err;
        EXPECT_TRUE(filesIn(dir).empty());
    }
    // And a frame that fits the cgroup renders in it.
    const CliRun fits = runFrugal(dir, {"render", "--size", "640x480", "--backend", "software", "-q", "-o", "fits.png"},
                                  "echo $$ > " + (cgroup.dir() / "cgroup.procs").string() + " &&");
    EXPECT_EQ(fits.status, 0) << fits.err;
    EXPECT_TRUE(fs::exists(dir / "fits.png"));
}

// Whether `--backend NAME` renders here at all; the tests of a broken set-up need the sound one.
bool backendWorks(const std::string& name) {
    // A directory of this test's own: CTest runs the tests of this file side by side, and a shared
    // one was emptied by one probe while another rendered into it.
    const fs::path dir =
        test::freshDir(std::string("FaultBackendProbe-") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    return runFrugal(dir, {"render", "--size", "32x24", "--backend", name, "-q"}).status == 0;
}

// frugal names its EGL platform (surfaceless, device) itself, so EGL_PLATFORM, which only picks
// what eglGetDisplay(EGL_DEFAULT_DISPLAY) means, and a missing X or Wayland display change nothing.
TEST(FaultCliTest, EglPlatformAndNoDisplayChangeNothing) {
    if (!backendWorks("egl")) FRUGAL_SKIP_IF_NO_GL("EGL");
    const fs::path dir = test::freshDir("FaultEglPlatform");
    for (const char* platform : {"bogus", "x11", "wayland", "gbm", "surfaceless"}) {
        SCOPED_TRACE(platform);
        const CliRun run = runFrugal(dir, {"render", "--size", "32x24", "--backend", "egl", "-q"},
                                     std::string("env -u DISPLAY -u WAYLAND_DISPLAY EGL_PLATFORM=") + platform);
        EXPECT_EQ(run.status, 0) << run.err;
        EXPECT_EQ(run.err, "");
        EXPECT_TRUE(readPng((dir / "frame.png").string()));
        fs::remove(dir / "frame.png");
    }
}

TEST(FaultCliTest, NoEglAtAllIsOneLineAndAutoFallsBackToOsMesa) {
    const fs::path dir = test::freshDir("FaultNoEgl");
    const std::string noVendor = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json";
    CliRun run = runFrugal(dir, {"render", "--size", "32x24", "--backend", "egl-surfaceless", "-q"}, noVendor);
    EXPECT_EQ(run.status, 3);
    EXPECT_EQ(run.err,
              "error: --backend egl-surfaceless: no usable GL context: egl-surfaceless: no EGL display: no EGL vendor "
              "library answered (libglvnd reads /usr/share/glvnd/egl_vendor.d; Debian: libegl-mesa0) "
              "(__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/vendor.json is set)\n");
    EXPECT_TRUE(filesIn(dir).empty());
    if (!backendWorks("osmesa")) FRUGAL_SKIP_IF_NO_GL("OSMesa, to fall back to");
    run = runFrugal(dir, {"render", "--size", "32x24", "--backend", "auto", "--json", "m.json", "-q"}, noVendor);
    EXPECT_EQ(run.status, 0) << run.err;
    EXPECT_EQ(run.err, "");
    EXPECT_EQ(test::readJson(dir / "m.json")["backend"], "osmesa");
}

// Mesa without its driver files: Mesa's own warnings ("libEGL warning: MESA-LOADER: failed to open
// swrast ...") are silenced, so the error is the one line; EGL_LOG_LEVEL set by the user is kept.
TEST(FaultCliTest, AMissingMesaDriverIsOneLineUnlessMesasLogIsAskedFor) {
    if (!backendWorks("egl")) FRUGAL_SKIP_IF_NO_GL("EGL");
    const fs::path dir = test::freshDir("FaultNoDriver");
    const CliRun run = runFrugal(dir, {"render", "--size", "32x24", "--backend", "egl-surfaceless", "-q"},
                                 "LIBGL_DRIVERS_PATH=/nonexistent");
    EXPECT_EQ(run.status, 3);
    EXPECT_EQ(run.err,
              "error: --backend egl-surfaceless: no usable GL context: egl-surfaceless: no EGL display (eglInitialize "
              "failed: EGL_NOT_INITIALIZED) (LIBGL_DRIVERS_PATH=/nonexistent is set)\n");
    EXPECT_TRUE(filesIn(dir).empty());
    const CliRun logged = runFrugal(dir, {"render", "--size", "32x24", "--backend", "egl-surfaceless", "-q"},
                                    "LIBGL_DRIVERS_PATH=/nonexistent EGL_LOG_LEVEL=warning");
    EXPECT_EQ(logged.status, 3);
    EXPECT_GT(logged.errLines().size(), 1u) << "Mesa's warnings, as asked" << logged.err;
}

// OSMesa dereferences a null screen for any GALLIUM_DRIVER but llvmpipe and softpipe (Mesa 22.3:
// a segfault); frugal refuses the others before it calls OSMesa.
TEST(FaultCliTest, AGalliumDriverOsMesaCannotServeIsRefusedBeforeTheCall) {
    if (!backendWorks("osmesa")) FRUGAL_SKIP_IF_NO_GL("OSMesa");
    const fs::path dir = test::freshDir("FaultOsMesaDriver");
    for (const char* driver : {"bogus", "i915", "swrast", "virpipe", "zink", "llvmpipe "}) {
        SCOPED_TRACE(driver);
        const CliRun run = runFrugal(dir, {"render", "--size", "32x24", "--backend", "osmesa", "-q"},
                                     "GALLIUM_DRIVER=" + test::shellQuoted(driver));
        EXPECT_EQ(run.status, 3);
        EXPECT_EQ(run.err,
                  "error: --backend osmesa: no usable GL context: osmesa: GALLIUM_DRIVER=" + std::string(driver) +
                      " is not a driver OSMesa has (llvmpipe, softpipe); unset it or pick one\n");
        EXPECT_TRUE(filesIn(dir).empty());
    }
    for (const char* driver : {"llvmpipe", "softpipe"}) {
        SCOPED_TRACE(driver);
        const CliRun run = runFrugal(dir, {"render", "--size", "32x24", "--backend", "osmesa", "-q"},
                                     std::string("GALLIUM_DRIVER=") + driver);
        EXPECT_EQ(run.status, 0) << run.err;
        fs::remove(dir / "frame.png");
    }
}

// virpipe on EGL with no virgl test server: Mesa 22 aborts the process inside eglInitialize; frugal
// refuses it first. Every other unknown driver makes EGL fail cleanly.
TEST(FaultCliTest, VirpipeWithNoServerIsRefusedBeforeEglAborts) {
    if (!backendWorks("egl")) FRUGAL_SKIP_IF_NO_GL("EGL");
    struct stat status {};
    if (::stat("/tmp/.virgl_test", &status) == 0) GTEST_SKIP() << "a virgl test server may be listening here";
    const fs::path dir = test::freshDir("FaultVirpipe");
    for (const char* backend : {"egl-surfaceless", "egl-device", "auto"}) {
        SCOPED_TRACE(backend);
        const CliRun run =
            runFrugal(dir, {"render", "--size", "32x24", "--backend", backend, "-q"}, "GALLIUM_DRIVER=virpipe");
        EXPECT_EQ(run.status, 3);
        ASSERT_EQ(run.errLines().size(), 1u) << run.err;
        EXPECT_NE(
            run.err.find("GALLIUM_DRIVER=virpipe needs a virgl test server on /tmp/.virgl_test and there is none"),
            std::string::npos)
            << run.err;
        EXPECT_TRUE(filesIn(dir).empty());
    }
}

// Two renders into one folder at once, writing the same frame files and then different ones: every
// file is whole and the same bytes as a render made alone; no temporary file collides or stays.
TEST(FaultCliTest, TwoProcessesRenderingIntoOneFolderLoseNothing) {
    const std::vector<std::string> render = {"render", "builtin:cubes", "--frames", "0:39", "--size",
                                             "96x72",  "--backend",     "software", "-q",   "-o"};
    const fs::path alone = test::freshDir("FaultTwoAlone");
    auto args = [&render](const std::string& pattern) {
        std::vector<std::string> a = render;
        a.push_back(pattern);
        return a;
    };
    ASSERT_EQ(runFrugal(alone, args("f_%04d.png")).status, 0);

    for (const bool sameFiles : {true, false}) {
        SCOPED_TRACE(sameFiles ? "the same files" : "different files");
        const fs::path dir = test::freshDir("FaultTwoProcesses");
        const char* prefixes[2] = {"a", sameFiles ? "a" : "b"};
        Background first(dir / "first", args(std::string(prefixes[0]) + "_%04d.png"));
        // The second works in the first's folder: its own `work` is a link to it.
        fs::create_directories(dir / "second");
        fs::create_directory_symlink(first.work(), dir / "second" / "work");
        Background second(dir / "second", args(std::string(prefixes[1]) + "_%04d.png"));
        EXPECT_EQ(first.wait(), 0) << first.err();
        EXPECT_EQ(second.wait(), 0) << second.err();
        EXPECT_EQ(first.err() + second.err(), "");
        std::vector<std::string> expected;
        for (const char* prefix : {"a", "b"})
            for (int frame = 0; frame < 40 && (!sameFiles || prefix[0] == 'a'); ++frame)
                expected.push_back(frameName(prefix, frame));
        EXPECT_EQ(filesIn(first.work()), expected);
        for (const std::string& file : filesIn(first.work()))
            EXPECT_TRUE(readAll(first.work() / file) == readAll(alone / ("f" + file.substr(1)))) << file;
    }
}

}  // namespace
}  // namespace frugal
