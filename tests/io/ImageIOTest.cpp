// Image files: PNG round trips through an independent decoder (stb_image), the one flip, the id and
// depth encodings, and atomic writes.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "TestSupport.h"
#include "io/ImageIO.h"

namespace frugal {
namespace {

Buffers gradient(int w, int h) {
    Buffers b;
    b.width = w;
    b.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            b.rgba.insert(b.rgba.end(), {std::uint8_t(x), std::uint8_t(y), std::uint8_t(x ^ y), 255});
            b.depth.push_back(std::uint32_t(y * w + x) * 0x1234u & kDepthMax);
            b.ids.push_back(std::uint32_t(0x01020304u * std::uint32_t(y * w + x + 1)));
        }
    return b;
}

TEST(ImageIOTest, ColourPngIsTopRowFirst) {
    const Buffers b = gradient(7, 5);
    const std::string path = (test::freshDir("ImageIOTest") / "c.png").string();
    ASSERT_TRUE(writeFileAtomic(path, encodeColorPng(b)));
    Result<DecodedImage> image = readPng(path);
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(image->width, 7);
    EXPECT_EQ(image->height, 5);
    EXPECT_EQ(image->channels, 4);
    for (int row = 0; row < 5; ++row)
        for (int x = 0; x < 7; ++x) {
            // File row 0 is window row height-1.
            const int y = 4 - row;
            const std::uint8_t* p = &image->pixels8[(std::size_t(row) * 7 + x) * 4];
            EXPECT_EQ(p[0], x);
            EXPECT_EQ(p[1], y);
            EXPECT_EQ(p[2], x ^ y);
        }
}

TEST(ImageIOTest, DepthPngHoldsTheTop16BitsAndPfmTheExactValue) {
    const Buffers b = gradient(3, 2);
    const std::filesystem::path dir = test::freshDir("ImageIOTestDepth");
    ASSERT_TRUE(writeFileAtomic((dir / "d.png").string(), encodeDepthPng(b)));
    Result<DecodedImage> image = readPng((dir / "d.png").string());
    ASSERT_TRUE(image) << image.error().message;
    EXPECT_EQ(image->bitDepth, 16);
    EXPECT_EQ(image->channels, 1);
    for (int row = 0; row < 2; ++row)
        for (int x = 0; x < 3; ++x) EXPECT_EQ(image->pixels16[row * 3 + x], b.depth[(1 - row) * 3 + x] >> 8);

    const Bytes pfm = encodeDepthPfm(b);
    const std::string header = "Pf\n3 2\n-1.0\n";
    ASSERT_EQ(pfm.size(), header.size() + 6 * 4);
    EXPECT_EQ(std::string(pfm.begin(), pfm.begin() + long(header.size())), header);
    float last = 0;
    std::memcpy(&last, &pfm[header.size() + 5 * 4], 4);  // PFM rows are bottom-up like Buffers
    EXPECT_FLOAT_EQ(last, float(double(b.depth[5]) / kDepthMax));
}

// Linear colour: PFM "PF" holds rgb exactly, bottom row first, alpha left out (values above 1 and
// below 0 kept); the 16-bit PNG clamps each channel to [0, 1], keeps alpha, says gAMA 1.0.
TEST(ImageIOTest, LinearPfmIsExactAndThePngSixteenBitsClamped) {
    LinearImage image{2,
                      2,
                      {0.25f, 2.5f, -1.0f, 1.0f, 0.5f, 0.0f, 1.0f, 0.5f,  //
                       1e-7f, 0.75f, 1.0f, 0.0f, 1.0f, 1.0f, 1.0f, 1.0f}};
    Result<Bytes> pfm = encodeLinearPfm(image);
    ASSERT_TRUE(pfm) << pfm.error().message;
    const std::string header = "PF\n2 2\n-1.0\n";
    ASSERT_EQ(pfm->size(), header.size() + 4 * 12);
    EXPECT_EQ(std::string(pfm->begin(), pfm->begin() + long(header.size())), header);
    for (std::size_t pixel = 0; pixel < 4; ++pixel)
        for (std::size_t c = 0; c < 3; ++c) {
            float value = 0;
            std::memcpy(&value, &(*pfm)[header.size() + (pixel * 3 + c) * 4], 4);
            EXPECT_EQ(value, image.rgba[pixel * 4 + c]) << pixel << " " << c;
        }

    const std::string path = (test::freshDir("ImageIOTestLinear") / "l.png").string();
    ASSERT_TRUE(writePng(path, image));
    const std::optional<std::string> bytes = readFile(path);
    ASSERT_TRUE(bytes);
    EXPECT_NE(bytes->find(std::string("gAMA\x00\x01\x86\xa0", 8)), std::string::npos) << "gAMA 100000";
    Result<DecodedImage> decoded = readPng(path);
    ASSERT_TRUE(decoded) << decoded.error().message;
    EXPECT_EQ(decoded->bitDepth, 16);
    EXPECT_EQ(decoded->channels, 4);
    // File row 0 is the image's top row (its row 1).
    const std::vector<std::uint16_t> expected = {0,     49151, 65535, 0,     65535, 65535, 65535, 65535,
                                                 16384, 65535, 0,     65535, 32768, 0,     65535, 32768};
    EXPECT_EQ(decoded->pixels16, expected);

    LinearImage wrong{3, 2, std::vector<float>(20)};
    EXPECT_FALSE(encodeLinearPfm(wrong));
    EXPECT_FALSE(encodeLinearPng(wrong));
}

TEST(ImageIOTest, IdPngBytesAreTheLittleEndianId) {
    const Buffers b = gradient(4, 3);
    const std::string path = (test::freshDir("ImageIOTestIds") / "i.png").string();
    ASSERT_TRUE(writeFileAtomic(path, encodeIdPng(b)));
    Result<DecodedImage> image = readPng(path);
    ASSERT_TRUE(image) << image.error().message;
    for (int row = 0; row < 3; ++row)
        for (int x = 0; x < 4; ++x) {
            const std::uint8_t* p = &image->pixels8[(std::size_t(row) * 4 + x) * 4];
            const std::uint32_t id = p[0] | (p[1] << 8) | (p[2] << 16) | (std::uint32_t(p[3]) << 24);
            EXPECT_EQ(id, b.ids[(2 - row) * 4 + x]);
        }
}

TEST(ImageIOTest, OutputSetLeavesNothingWhenAWriteFails) {
    const std::filesystem::path dir = test::freshDir("ImageIOTestAtomic");
    OutputSet set;
    set.add((dir / "a.png").string(), Bytes{1, 2, 3});
    set.add((dir / "missing-folder" / "b.png").string(), Bytes{4});
    Result<bool> result = set.commit();
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message, (dir / "missing-folder" / "b.png").string() + ": cannot write: No such file or directory");
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << "no final file and no temporary file may remain";
}

// writeFrame: the files `frugal render` writes, as one set; depth by its extension in any case.
TEST(ImageIOTest, WriteFrameWritesTheSetOrNothing) {
    const std::filesystem::path dir = test::freshDir("ImageIOTestFrame");
    const Buffers b = gradient(8, 4);
    Frame frame;
    frame.color = ColorImage{b.width, b.height, b.rgba};
    frame.depth.width = b.width;
    frame.depth.height = b.height;
    frame.depth.values = b.depth;
    const std::string color = (dir / "c.png").string(), depth = (dir / "d.PFM").string();
    ASSERT_TRUE(writeFrame({color, depth, "", ""}, frame));
    const Result<Bytes> png = encodeColorPng(frame.color);
    ASSERT_TRUE(png);
    EXPECT_EQ(test::readAll(color), std::string(png->begin(), png->end()));
    const Result<Bytes> pfm = encodeDepthPfm(frame.depth);
    ASSERT_TRUE(pfm);
    EXPECT_EQ(test::readAll(depth), std::string(pfm->begin(), pfm->end()));

    const std::string other = (dir / "other.png").string(), ids = (dir / "i.png").string();
    Result<bool> noIds = writeFrame({other, "", ids, ""}, frame);
    ASSERT_FALSE(noIds);
    EXPECT_EQ(noIds.error().message, "ids " + ids + ": the frame has no ids (Settings::ids)");
    Result<bool> failed = writeFrame({other, (dir / "missing-folder" / "d.png").string(), "", ""}, frame);
    ASSERT_FALSE(failed);
    EXPECT_FALSE(std::filesystem::exists(other)) << "a set is written whole or not at all";
}

TEST(ImageIOTest, OutputSetTakesBackEarlierFilesWhenALaterRenameFails) {
    const std::filesystem::path dir = test::freshDir("ImageIOTestRollback");
    test::writeFile(dir / "old.png", "old contents");
    // A non-empty folder where the third file should go: writing its temporary works, renaming
    // the finished file over the folder does not.
    test::writeFile(dir / "blocked.png" / "inside", "x");
    OutputSet set;
    set.add((dir / "old.png").string(), Bytes{'n', 'e', 'w'});
    set.add((dir / "fresh.png").string(), Bytes{1});
    set.add((dir / "blocked.png").string(), Bytes{2});
    Result<bool> result = set.commit();
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message.rfind((dir / "blocked.png").string() + ": cannot rename the finished file into place: ", 0), 0u)
        << result.error().message;
    EXPECT_EQ(test::readAll(dir / "old.png"), "old contents");
    EXPECT_EQ(test::filesIn(dir), (std::vector<std::string>{"blocked.png", "old.png"}))
        << "the new file is taken back; no temporary or backup remains";
}

TEST(ImageIOTest, OutputSetReplacesExistingFilesAndLeavesNoBackup) {
    const std::filesystem::path dir = test::freshDir("ImageIOTestReplace");
    test::writeFile(dir / "a.png", "old");
    OutputSet set;
    set.add((dir / "a.png").string(), Bytes{'n', 'e', 'w'});
    set.add((dir / "b.png").string(), Bytes{'b'});
    ASSERT_TRUE(set.commit());
    EXPECT_EQ(test::readAll(dir / "a.png"), "new");
    EXPECT_EQ(test::filesIn(dir), (std::vector<std::string>{"a.png", "b.png"}));
}

TEST(ImageIOTest, PngEncoderRefusesWhatPngCannotHoldAndWritesNothing) {
    const std::uint8_t pixel[8] = {};
    EXPECT_EQ(encodePng(1, 1, 5, 8, pixel).error().message, "PNG encoder: channels must be 1 to 4, got 5");
    EXPECT_EQ(encodePng(1, 1, 0, 8, pixel).error().message, "PNG encoder: channels must be 1 to 4, got 0");
    EXPECT_EQ(encodePng(1, 1, 4, 12, pixel).error().message, "PNG encoder: bit depth must be 8 or 16, got 12");
    EXPECT_EQ(encodePng(0, 1, 4, 8, pixel).error().message, "PNG encoder: width and height must be at least 1, got 0x1");
    for (int channels = 1; channels <= 4; ++channels) EXPECT_TRUE(encodePng(1, 1, channels, 16, pixel)) << channels;

    const std::filesystem::path dir = test::freshDir("ImageIOTestEncoderError");
    OutputSet set;
    set.add((dir / "good.png").string(), encodePng(1, 1, 4, 8, pixel));
    set.add((dir / "bad.png").string(), encodePng(1, 1, 7, 8, pixel));
    Result<bool> result = set.commit();
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message, (dir / "bad.png").string() + ": cannot encode: PNG encoder: channels must be 1 to 4, got 7");
    EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(ImageIOTest, ReadPngRejectsGarbage) {
    const std::filesystem::path path = test::freshDir("ImageIOTestGarbage") / "x.png";
    test::writeFile(path, "not a png at all");
    Result<DecodedImage> image = readPng(path.string());
    ASSERT_FALSE(image);
    EXPECT_EQ(image.error().message.rfind(path.string() + ": not a PNG", 0), 0u) << image.error().message;
}

}  // namespace
}  // namespace frugal
