#include "io/ImageIO.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <stb_image.h>

namespace frugal {

namespace {

void put32(Bytes& out, std::uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out.push_back(std::uint8_t(v >> shift));
}

void chunk(Bytes& out, const char type[4], const Bytes& data) {
    put32(out, std::uint32_t(data.size()));
    const std::size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    put32(out, std::uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
}

}  // namespace

std::vector<std::uint8_t> flipRows(const std::uint8_t* rows, int width, int height, int bytesPerPixel) {
    const std::size_t stride = std::size_t(width) * bytesPerPixel;
    std::vector<std::uint8_t> out(stride * height);
    for (int y = 0; y < height; ++y) std::memcpy(&out[stride * (height - 1 - y)], rows + stride * y, stride);
    return out;
}

Result<Bytes> encodePng(int width, int height, int channels, int bitDepth, const void* rowsTopFirst) {
    if (channels < 1 || channels > 4) return Error{"PNG encoder: channels must be 1 to 4, got " + std::to_string(channels)};
    if (bitDepth != 8 && bitDepth != 16) return Error{"PNG encoder: bit depth must be 8 or 16, got " + std::to_string(bitDepth)};
    if (width < 1 || height < 1)
        return Error{"PNG encoder: width and height must be at least 1, got " + std::to_string(width) + "x" +
                     std::to_string(height)};
    const std::size_t sampleBytes = bitDepth / 8;
    const std::size_t stride = std::size_t(width) * channels * sampleBytes;
    // Filter type 0 (none) per row; PNG stores 16-bit samples big-endian.
    Bytes raw((stride + 1) * height);
    const auto* src = static_cast<const std::uint8_t*>(rowsTopFirst);
    for (int y = 0; y < height; ++y) {
        std::uint8_t* row = &raw[(stride + 1) * y];
        row[0] = 0;
        const std::uint8_t* in = src + stride * y;
        if (bitDepth == 8) {
            std::memcpy(row + 1, in, stride);
        } else {
            for (std::size_t i = 0; i < stride; i += 2) {
                std::uint16_t v;
                std::memcpy(&v, in + i, 2);
                row[1 + i] = std::uint8_t(v >> 8);
                row[2 + i] = std::uint8_t(v & 0xFF);
            }
        }
    }
    if (raw.size() > std::numeric_limits<uLong>::max() / 2)
        return Error{"PNG encoder: " + std::to_string(raw.size()) + " bytes of pixels is more than zlib takes at once"};
    uLongf packedSize = compressBound(uLong(raw.size()));
    Bytes packed(packedSize);
    if (const int z = compress2(packed.data(), &packedSize, raw.data(), uLong(raw.size()), 6); z != Z_OK)
        return Error{"PNG encoder: zlib compress2 failed on " + std::to_string(raw.size()) + " bytes: " + zError(z)};
    packed.resize(packedSize);

    static const std::uint8_t kColorType[5] = {0, 0, 4, 2, 6};  // by channels: grey, grey+alpha, RGB, RGBA
    Bytes out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    Bytes header;
    put32(header, std::uint32_t(width));
    put32(header, std::uint32_t(height));
    header.push_back(std::uint8_t(bitDepth));
    header.push_back(kColorType[channels]);
    header.push_back(0);  // deflate
    header.push_back(0);  // adaptive filtering
    header.push_back(0);  // no interlace
    chunk(out, "IHDR", header);
    chunk(out, "IDAT", packed);
    chunk(out, "IEND", {});
    return out;
}

Result<Bytes> encodeColorPng(const Buffers& b) {
    const std::vector<std::uint8_t> rows = flipRows(b.rgba.data(), b.width, b.height, 4);
    return encodePng(b.width, b.height, 4, 8, rows.data());
}

Result<Bytes> encodeDepthPng(const Buffers& b) {
    std::vector<std::uint16_t> depth16(b.pixelCount());
    for (std::size_t i = 0; i < depth16.size(); ++i) depth16[i] = std::uint16_t(b.depth[i] >> 8);
    const std::vector<std::uint8_t> rows = flipRows(reinterpret_cast<const std::uint8_t*>(depth16.data()), b.width, b.height, 2);
    return encodePng(b.width, b.height, 1, 16, rows.data());
}

Bytes encodeDepthPfm(const Buffers& b) {
    // PFM stores rows bottom-up already, little-endian when the scale is negative.
    const std::string header = "Pf\n" + std::to_string(b.width) + " " + std::to_string(b.height) + "\n-1.0\n";
    Bytes out(header.begin(), header.end());
    out.reserve(out.size() + b.pixelCount() * 4);
    for (std::uint32_t d : b.depth) {
        const float z = float(double(d) / double(kDepthMax));
        std::uint8_t bytes[4];
        std::memcpy(bytes, &z, 4);
        out.insert(out.end(), bytes, bytes + 4);
    }
    return out;
}

Result<Bytes> encodeIdPng(const Buffers& b) {
    std::vector<std::uint8_t> bytes(b.pixelCount() * 4);
    for (std::size_t i = 0; i < b.ids.size(); ++i)
        for (int k = 0; k < 4; ++k) bytes[4 * i + k] = std::uint8_t(b.ids[i] >> (8 * k));
    const std::vector<std::uint8_t> rows = flipRows(bytes.data(), b.width, b.height, 4);
    return encodePng(b.width, b.height, 4, 8, rows.data());
}

namespace {

std::string temporaryName(const std::string& path) {
    return path + ".tmp-" + std::to_string(::getpid());
}

Result<bool> writeTemporary(const std::string& path, const std::string& temp, const Bytes& bytes) {
    std::FILE* file = std::fopen(temp.c_str(), "wb");
    if (!file) return Error{path + ": cannot write: " + std::strerror(errno)};
    const bool written = std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    const int savedErrno = errno;
    const bool closed = std::fclose(file) == 0;
    if (!written || !closed) {
        std::remove(temp.c_str());
        return Error{path + ": write failed after " + std::to_string(bytes.size()) + " bytes requested: " +
                     std::strerror(written ? errno : savedErrno)};
    }
    return true;
}

}  // namespace

Result<bool> writeFileAtomic(const std::string& path, Result<Bytes> bytes) {
    OutputSet set;
    set.add(path, std::move(bytes));
    return set.commit();
}

void OutputSet::add(std::string path, Result<Bytes> bytes) { files_.emplace_back(std::move(path), std::move(bytes)); }

Result<bool> OutputSet::commit() {
    for (const auto& [path, bytes] : files_)
        if (!bytes) return Error{path + ": cannot encode: " + bytes.error()};

    std::vector<std::string> temps;
    const auto removeAll = [](const std::vector<std::string>& paths) {
        for (const std::string& p : paths) std::remove(p.c_str());
    };
    for (const auto& [path, bytes] : files_) {
        const std::string temp = temporaryName(path);
        Result<bool> ok = writeTemporary(path, temp, *bytes);
        if (!ok) {
            removeAll(temps);
            return ok;
        }
        temps.push_back(temp);
    }

    // Before a file is replaced its old contents get a second name (a hard link: the file itself
    // never disappears), so a later failed rename can put them back.
    std::vector<std::string> backups(files_.size());
    const auto dropBackups = [&backups] {
        for (const std::string& b : backups)
            if (!b.empty()) std::remove(b.c_str());
    };
    for (std::size_t i = 0; i < files_.size(); ++i) {
        const std::string& path = files_[i].first;
        struct stat status {};
        if (::lstat(path.c_str(), &status) != 0 || S_ISDIR(status.st_mode)) continue;  // nothing to keep
        const std::string backup = path + ".old-" + std::to_string(::getpid());
        std::remove(backup.c_str());
        if (::link(path.c_str(), backup.c_str()) != 0) {
            const std::string why = std::strerror(errno);
            dropBackups();
            removeAll(temps);
            return Error{path + ": cannot keep the old file while replacing it: " + why};
        }
        backups[i] = backup;
    }
    for (std::size_t i = 0; i < files_.size(); ++i) {
        if (std::rename(temps[i].c_str(), files_[i].first.c_str()) == 0) continue;
        const std::string why = std::strerror(errno);
        for (std::size_t j = 0; j < i; ++j) {  // take back what was renamed
            if (backups[j].empty()) std::remove(files_[j].first.c_str());
            else if (std::rename(backups[j].c_str(), files_[j].first.c_str()) == 0) backups[j].clear();
        }
        dropBackups();
        removeAll(std::vector<std::string>(temps.begin() + std::ptrdiff_t(i), temps.end()));
        return Error{files_[i].first + ": cannot rename the finished file into place: " + why};
    }
    dropBackups();
    files_.clear();
    return true;
}

Result<DecodedImage> readPng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path + ": cannot open"};
    const std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    DecodedImage image;
    if (data.size() > std::size_t(INT32_MAX)) return Error{path + ": file too large"};
    const int size = int(data.size());
    int w = 0, h = 0, n = 0;
    if (!stbi_info_from_memory(data.data(), size, &w, &h, &n))
        return Error{path + ": not a PNG: " + stbi_failure_reason()};
    image.width = w;
    image.height = h;
    image.channels = n;
    if (stbi_is_16_bit_from_memory(data.data(), size)) {
        image.bitDepth = 16;
        stbi_us* pixels = stbi_load_16_from_memory(data.data(), size, &w, &h, &n, 0);
        if (!pixels) return Error{path + ": cannot decode: " + stbi_failure_reason()};
        image.pixels16.assign(pixels, pixels + std::size_t(w) * h * n);
        stbi_image_free(pixels);
    } else {
        stbi_uc* pixels = stbi_load_from_memory(data.data(), size, &w, &h, &n, 0);
        if (!pixels) return Error{path + ": cannot decode: " + stbi_failure_reason()};
        image.pixels8.assign(pixels, pixels + std::size_t(w) * h * n);
        stbi_image_free(pixels);
    }
    return image;
}

}  // namespace frugal
