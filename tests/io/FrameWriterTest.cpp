// FrameWriter (frugal/Files.h): frames' files written on threads of their own, in order, each set
// whole, the queue bounded, the first error stopping it, memory handed back for the next frame.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

// A small frame whose pixels say which frame it is.
Frame numbered(int n, bool ids = true) {
    Frame frame;
    const int w = 40, h = 30;
    frame.color = {w, h, std::vector<std::uint8_t>(std::size_t(w * h * 4), std::uint8_t(n))};
    frame.depth = {
        w,     h,   std::vector<std::uint32_t>(std::size_t(w * h), std::uint32_t(n * 1000)), DepthFormat::D24, 0.5f,
        50.0f, true};
    if (ids) frame.ids = {w, h, std::vector<std::uint32_t>(std::size_t(w * h), std::uint32_t(n + 1))};
    return frame;
}

FramePaths pathsOf(const std::filesystem::path& dir, int n) {
    const std::string stem = (dir / ("f" + std::to_string(n))).string();
    return {stem + ".png", stem + "-depth.png", stem + "-ids.png", ""};
}

TEST(FrameWriterTest, WritesEveryFrameInOrderAndHandsMemoryBack) {
    const auto dir = test::freshDir("FrameWriterOrder");
    Result<FrameWriter> writer = FrameWriter::create({.threads = 2, .queue = 3, .pngLevel = kAutoPngLevel});
    ASSERT_TRUE(writer);
    std::vector<std::size_t> order;
    bool reused = false;
    for (int n = 0; n < 12; ++n) {
        Frame frame = numbered(n);
        ASSERT_TRUE(writer->write(pathsOf(dir, n), frame));
        // What comes back is a frame already written (its memory), or nothing.
        reused = reused || !frame.color.rgba.empty();
        for (const FrameWriter::Written& w : writer->takeWritten()) {
            order.push_back(w.index);
            EXPECT_GT(w.encodeMs, 0.0);
        }
    }
    ASSERT_TRUE(writer->finish());
    for (const FrameWriter::Written& w : writer->takeWritten()) order.push_back(w.index);
    EXPECT_TRUE(reused);
    ASSERT_EQ(order.size(), 12u);
    for (std::size_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
    EXPECT_EQ(test::filesIn(dir).size(), 36u) << "three files a frame, no temporary left";
    for (int n = 0; n < 12; ++n) {
        Result<DecodedImage> color = readPng(pathsOf(dir, n).color);
        ASSERT_TRUE(color);
        EXPECT_EQ(color->pixels8.front(), std::uint8_t(n));
        Result<DecodedImage> ids = readPng(pathsOf(dir, n).ids);
        ASSERT_TRUE(ids);
        EXPECT_EQ(ids->pixels8.front(), std::uint8_t(n + 1));
        Result<DecodedImage> depth = readPng(pathsOf(dir, n).depth);
        ASSERT_TRUE(depth);
        EXPECT_EQ(depth->bitDepth, 16);
    }
}

TEST(FrameWriterTest, TheFileIsWhatWriteFrameWrites) {
    const auto dir = test::freshDir("FrameWriterSame");
    const Frame frame = numbered(5);
    ASSERT_TRUE(writeFrame({(dir / "a.png").string(), (dir / "a.pfm").string(), "", ""}, frame, 1));
    Result<FrameWriter> writer = FrameWriter::create({.threads = 1, .queue = 1, .pngLevel = 1});
    ASSERT_TRUE(writer);
    Frame copy = frame;
    ASSERT_TRUE(writer->write({(dir / "b.png").string(), (dir / "b.pfm").string(), "", ""}, copy));
    ASSERT_TRUE(writer->finish());
    EXPECT_EQ(test::readAll(dir / "a.png"), test::readAll(dir / "b.png"));
    EXPECT_EQ(test::readAll(dir / "a.pfm"), test::readAll(dir / "b.pfm"));
}

TEST(FrameWriterTest, TheQueueIsBounded) {
    // One frame held at most: handing over frame n waits until frame n - 1 is written (frame n
    // itself may be written too by the time write() returns: the worker does not wait).
    const auto dir = test::freshDir("FrameWriterQueue");
    Result<FrameWriter> writer = FrameWriter::create({.threads = 1, .queue = 1, .pngLevel = kAutoPngLevel});
    ASSERT_TRUE(writer);
    std::vector<std::size_t> indices;
    for (int n = 0; n < 5; ++n) {
        Frame frame = numbered(n);
        ASSERT_TRUE(writer->write(pathsOf(dir, n), frame));
        for (const FrameWriter::Written& w : writer->takeWritten()) indices.push_back(w.index);
        EXPECT_GE(indices.size(), std::size_t(n)) << "frame " << n << " handed over before frame " << n - 1
                                                  << " was written";
    }
    ASSERT_TRUE(writer->finish());
    for (const FrameWriter::Written& w : writer->takeWritten()) indices.push_back(w.index);
    EXPECT_EQ(indices, (std::vector<std::size_t>{0, 1, 2, 3, 4})) << "in order, each once";
}

TEST(FrameWriterTest, TheFirstErrorStopsItAndNothingHalfWrittenIsLeft) {
    const auto dir = test::freshDir("FrameWriterError");
    Result<FrameWriter> writer = FrameWriter::create({.threads = 2, .queue = 2, .pngLevel = kAutoPngLevel});
    ASSERT_TRUE(writer);
    Frame good = numbered(0);
    ASSERT_TRUE(writer->write(pathsOf(dir, 0), good));
    Frame bad = numbered(1);
    FramePaths missing = pathsOf(dir / "missing-folder", 1);
    missing.depth = pathsOf(dir, 1).depth;  // its own folder exists: the set must not half appear
    ASSERT_TRUE(writer->write(missing, bad));
    Result<bool> later = true;
    for (int n = 2; n < 6 && later; ++n) {
        Frame frame = numbered(n);
        later = writer->write(pathsOf(dir, n), frame);
    }
    const Result<bool> finished = writer->finish();
    ASSERT_FALSE(finished);
    EXPECT_EQ(finished.error().message, missing.color + ": cannot write: No such file or directory");
    EXPECT_EQ(finished.error().kind, ErrorKind::Io);
    // Frame 0 whole; frame 1 not at all (its depth file neither); nothing after it; no temporary.
    EXPECT_EQ(test::filesIn(dir), (std::vector<std::string>{"f0-depth.png", "f0-ids.png", "f0.png"}));
}

TEST(FrameWriterTest, BadRequestsGetOneLine) {
    Result<FrameWriter> level = FrameWriter::create({.threads = 0, .queue = 0, .pngLevel = 13});
    ASSERT_FALSE(level);
    EXPECT_EQ(level.error().message, "png-level 13: must be 0 (fastest, largest) to 12 (smallest, slowest), or auto (-1)");
    EXPECT_TRUE(level.error().aboutSetting);
    EXPECT_FALSE(FrameWriter::create({.threads = -1, .queue = 0, .pngLevel = 1}));
    EXPECT_FALSE(FrameWriter::create({.threads = 0, .queue = 5000, .pngLevel = 1}));

    const auto dir = test::freshDir("FrameWriterNoIds");
    FrameWriter writer;
    Frame frame = numbered(0, false);
    const Result<bool> queued = writer.write(pathsOf(dir, 0), frame);
    ASSERT_FALSE(queued);
    EXPECT_EQ(queued.error().message, "ids " + pathsOf(dir, 0).ids + ": the frame has no ids (Settings::ids)");
    EXPECT_FALSE(frame.color.rgba.empty()) << "a refused frame stays the caller's";
    EXPECT_TRUE(writer.finish()) << "a refused frame is not an error of the writer";
    EXPECT_TRUE(test::filesIn(dir).empty());
}

TEST(FrameWriterTest, AnImageTheFrameDoesNotHoldIsOneLineAndNoFile) {
    const auto dir = test::freshDir("FrameWriterNoDepth");
    Frame frame = numbered(0);
    frame.depth.values.clear();  // rendered with ReadBack{.depth = false}
    FrameWriter writer;
    const Result<bool> queued = writer.write(pathsOf(dir, 0), frame);
    ASSERT_FALSE(queued);
    EXPECT_EQ(queued.error().message,
              "depth " + pathsOf(dir, 0).depth + ": the frame has no depth (rendered with ReadBack{.depth = false})");
    const Result<bool> direct = writeFrame({"", (dir / "d.pfm").string(), "", ""}, frame);
    ASSERT_FALSE(direct);
    EXPECT_EQ(direct.error().message, "depth " + (dir / "d.pfm").string() +
                                  ": the frame has no depth (rendered with ReadBack{.depth = false})");
    // An image whose values do not fill it (a library caller's mistake) is refused, never read past.
    Frame short_ = numbered(1);
    short_.color.rgba.resize(10);
    short_.depth.values.resize(7);
    EXPECT_EQ(writePng((dir / "c.png").string(), short_.color).error().message,
              (dir / "c.png").string() + ": cannot encode: PNG encoder: the colour image holds 10 values, 40x30 needs 4800");
    EXPECT_EQ(writePfm((dir / "d.pfm").string(), short_.depth).error().message,
              (dir / "d.pfm").string() + ": cannot encode: PFM encoder: the depth image holds 7 values, 40x30 needs 1200");
    EXPECT_TRUE(writer.finish());
    EXPECT_TRUE(test::filesIn(dir).empty());
}

TEST(FrameWriterTest, TheDestructorFinishesTheFramesGiven) {
    const auto dir = test::freshDir("FrameWriterDestructor");
    {
        FrameWriter writer;
        for (int n = 0; n < 4; ++n) {
            Frame frame = numbered(n);
            ASSERT_TRUE(writer.write(pathsOf(dir, n), frame));
        }
    }
    EXPECT_EQ(test::filesIn(dir).size(), 12u);
}

}  // namespace
}  // namespace frugal
