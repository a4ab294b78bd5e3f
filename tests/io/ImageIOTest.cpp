// Image files: PNG round trips through an independent decoder (stb_image), the one flip, the id and
// depth encodings, and atomic writes.
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

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
    ASSERT_TRUE(image) << image.error();
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
    ASSERT_TRUE(image) << image.error();
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

TEST(ImageIOTest, IdPngBytesAreTheLittleEndianId) {
    const Buffers b = gradient(4, 3);
    const std::string path = (test::freshDir("ImageIOTestIds") / "i.png").string();
    ASSERT_TRUE(writeFileAtomic(path, encodeIdPng(b)));
    Result<DecodedImage> image = readPng(path);
    ASSERT_TRUE(image) << image.error();
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
    EXPECT_EQ(result.error(), (dir / "missing-folder" / "b.png").string() + ": cannot write: No such file or directory");
    EXPECT_TRUE(std::filesystem::is_empty(dir)) << "no final file and no temporary file may remain";
}

TEST(ImageIOTest, ReadPngRejectsGarbage) {
    const std::filesystem::path path = test::freshDir("ImageIOTestGarbage") / "x.png";
    test::writeFile(path, "not a png at all");
    Result<DecodedImage> image = readPng(path.string());
    ASSERT_FALSE(image);
    EXPECT_EQ(image.error().rfind(path.string() + ": not a PNG", 0), 0u) << image.error();
}

}  // namespace
}  // namespace frugal
