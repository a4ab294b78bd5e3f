// The atomic writer (OutputSet, writeFileAtomic) under faults: a full device, a file-size limit, a
// folder that refuses files, a temporary name already taken, and several processes writing one
// file at once. Whatever happens, no temporary or backup file stays and no file is half written.
#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "TestSupport.h"
#include "io/ImageIO.h"
#include "io/Interrupt.h"

namespace frugal {
namespace {

namespace fs = std::filesystem;

bool isCharacterDevice(const char* path) {
    struct stat status {};
    return ::lstat(path, &status) == 0 && S_ISCHR(status.st_mode);
}

// Through links in the test's folder: a writer that renamed over them (the bug this guards
// against, as root) replaces the links, not the machine's /dev/null and /dev/full.
TEST(WriterFaultTest, ADeviceIsWrittenInPlaceAndNeverReplaced) {
    const fs::path dir = test::freshDir("WriterFaultDevice");
    fs::create_symlink("/dev/null", dir / "null.png");
    fs::create_symlink("/dev/full", dir / "full.png");
    EXPECT_TRUE(writeFileAtomic((dir / "null.png").string(), Bytes{1, 2, 3}));
    Result<bool> full = writeFileAtomic((dir / "full.png").string(), Bytes{1, 2, 3});
    ASSERT_FALSE(full);
    EXPECT_EQ(full.error().message, (dir / "full.png").string() + ": write failed after 0 of 3 bytes: No space left on device");
    EXPECT_TRUE(fs::is_symlink(dir / "null.png") && fs::is_symlink(dir / "full.png"))
        << "written in place, not replaced";
    EXPECT_EQ(test::filesIn(dir), (std::vector<std::string>{"full.png", "null.png"}));
    EXPECT_TRUE(isCharacterDevice("/dev/null") && isCharacterDevice("/dev/full"));
}

TEST(WriterFaultTest, AFullDeviceInASetLeavesNoOtherFile) {
    const fs::path dir = test::freshDir("WriterFaultFullSet");
    fs::create_symlink("/dev/full", dir / "depth.png");  // a set member that is a device
    OutputSet set;
    set.add((dir / "colour.png").string(), Bytes(1000, 7));
    set.add((dir / "depth.png").string(), Bytes(1000, 8));
    Result<bool> result = set.commit();
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message,
              (dir / "depth.png").string() + ": write failed after 0 of 1000 bytes: No space left on device");
    EXPECT_EQ(test::filesIn(dir), std::vector<std::string>{"depth.png"});
    EXPECT_TRUE(fs::is_symlink(dir / "depth.png"));
}

// A link is followed: the file it leads to is replaced (made, when missing), and the link stays. A
// magic link to an open descriptor (/dev/stdout is one, to /proc/self/fd/1) reaches the file that
// descriptor has open: a shell's `> out.json` gets the JSON. Links in the test's folder stand in
// for the machine's own.
TEST(WriterFaultTest, ALinkIsFollowedAndStaysALink) {
    const fs::path dir = test::freshDir("WriterFaultLink");
    fs::create_directory(dir / "sub");
    test::writeFile(dir / "sub" / "old.png", "old");
    fs::create_symlink("sub/old.png", dir / "to-old.png");
    fs::create_symlink("sub/new.png", dir / "to-new.png");
    fs::create_symlink("missing/x.png", dir / "dangling.png");
    OutputSet set;
    set.add((dir / "to-old.png").string(), Bytes{'o'});
    set.add((dir / "to-new.png").string(), Bytes{'n'});
    ASSERT_TRUE(set.commit());
    EXPECT_EQ(test::readAll(dir / "sub" / "old.png"), "o");
    EXPECT_EQ(test::readAll(dir / "sub" / "new.png"), "n");
    EXPECT_TRUE(fs::is_symlink(dir / "to-old.png") && fs::is_symlink(dir / "to-new.png"));
    EXPECT_EQ(test::filesIn(dir / "sub"), (std::vector<std::string>{"new.png", "old.png"}));

    Result<bool> dangling = writeFileAtomic((dir / "dangling.png").string(), Bytes{1});
    ASSERT_FALSE(dangling);
    EXPECT_EQ(dangling.error().message, (dir / "dangling.png").string() + ": cannot write: No such file or directory");
    EXPECT_TRUE(fs::is_symlink(dir / "dangling.png"));

    const int fd = ::open((dir / "redirect.json").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ASSERT_GE(fd, 0);
    fs::create_symlink("/proc/self/fd/" + std::to_string(fd), dir / "stdout.json");
    EXPECT_TRUE(writeFileAtomic((dir / "stdout.json").string(), Bytes{'{', '}'}));
    ::close(fd);
    EXPECT_EQ(test::readAll(dir / "redirect.json"), "{}");
    EXPECT_TRUE(fs::is_symlink(dir / "stdout.json"));
}

// `ulimit -f`: a write past the limit fails with EFBIG once SIGXFSZ is ignored (installInterruptHandler
// does that), instead of the signal's core dump. In a child, which may lower its own limit.
TEST(WriterFaultTest, AFileSizeLimitFailsTheWriteAndLeavesNoTemporaryFile) {
    const fs::path dir = test::freshDir("WriterFaultFileSize");
    const std::string path = (dir / "big.png").string();
    EXPECT_EXIT(
        {
            installInterruptHandler();
            rlimit limit;
            limit.rlim_cur = limit.rlim_max = 100;
            setrlimit(RLIMIT_FSIZE, &limit);
            // (The child's stderr is a file under the same limit: only the exit status tells.)
            Result<bool> result = writeFileAtomic(path, Bytes(1000, 1));
            if (result || result.error().message != path + ": write failed after 100 of 1000 bytes: File too large")
                std::_Exit(1);
            std::_Exit(test::filesIn(dir).empty() ? 0 : 2);
        },
        ::testing::ExitedWithCode(0), "");
}

TEST(WriterFaultTest, AFolderThatRefusesFilesGivesOneErrorAndNoFile) {
    const fs::path dir = test::freshDir("WriterFaultFolder");
    test::writeFile(dir / "file.txt", "a regular file");
    const std::string underAFile = (dir / "file.txt" / "x.png").string();
    Result<bool> result = writeFileAtomic(underAFile, Bytes{1});
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message, underAFile + ": cannot write: Not a directory");
    EXPECT_EQ(test::filesIn(dir), std::vector<std::string>{"file.txt"});

    // sysfs takes no new file, even from root (whom permission bits do not stop).
    if (!fs::is_directory("/sys/kernel")) GTEST_SKIP() << "no sysfs mounted at /sys";
    result = writeFileAtomic("/sys/frugal-test.png", Bytes{1});
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message.rfind("/sys/frugal-test.png: cannot write: ", 0), 0u) << result.error().message;
    EXPECT_FALSE(fs::exists("/sys/frugal-test.png"));
}

// A name where the temporary file would go is taken (another writer's, or a link planted there): it
// is neither followed nor removed, and the file is written under another temporary name.
TEST(WriterFaultTest, ATakenTemporaryNameIsLeftAloneAndNotFollowed) {
    const fs::path dir = test::freshDir("WriterFaultTaken");
    test::writeFile(dir / "victim", "keep me");
    const std::string taken = "a.png.tmp-" + std::to_string(::getpid());
    fs::create_symlink(dir / "victim", dir / taken);
    ASSERT_TRUE(writeFileAtomic((dir / "a.png").string(), Bytes{'n', 'e', 'w'}));
    EXPECT_EQ(test::readAll(dir / "a.png"), "new");
    EXPECT_EQ(test::readAll(dir / "victim"), "keep me");
    EXPECT_EQ(test::filesIn(dir), (std::vector<std::string>{"a.png", taken, "victim"}));
}

// Four processes replace one file 200 times each, with contents of different lengths: the file is
// always one writer's whole contents, and no temporary or backup file remains.
TEST(WriterFaultTest, ProcessesWritingOneFileAtOnceLeaveOneWholeFile) {
    const fs::path dir = test::freshDir("WriterFaultConcurrent");
    const std::string path = (dir / "shared.png").string();
    const auto contents = [](int writer) { return std::string(std::size_t(1000 + 977 * writer), char('a' + writer)); };
    constexpr int kWriters = 4;
    pid_t children[kWriters];
    for (int writer = 0; writer < kWriters; ++writer) {
        const std::string text = contents(writer);
        const Bytes bytes(text.begin(), text.end());
        children[writer] = fork();
        ASSERT_GE(children[writer], 0);
        if (children[writer] == 0) {
            for (int round = 0; round < 200; ++round)
                if (Result<bool> written = writeFileAtomic(path, bytes); !written) {
                    std::fprintf(stderr, "%s\n", written.error().message.c_str());
                    _exit(1);
                }
            _exit(0);
        }
    }
    for (pid_t child : children) {
        int status = 0;
        ASSERT_EQ(waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a writer failed";
    }
    const std::string last = test::readAll(path);
    bool whole = false;
    for (int writer = 0; writer < kWriters; ++writer) whole = whole || last == contents(writer);
    EXPECT_TRUE(whole) << last.size() << " bytes";
    EXPECT_EQ(test::filesIn(dir), std::vector<std::string>{"shared.png"});
}

}  // namespace
}  // namespace frugal
