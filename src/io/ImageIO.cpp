#include "io/ImageIO.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <stb_image.h>
#include <zlib.h>

#include <frugal/Files.h>
#include <frugal/Renderer.h>

#include "base/Format.h"
#include "io/Interrupt.h"
#include "scene/ImageCheck.h"

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

Result<Bytes> encodePng(int width, int height, int channels, int bitDepth, const void* rowsTopFirst,
                        const PngText& text) {
    if (channels < 1 || channels > 4) return Error{"PNG encoder: channels must be 1 to 4, got " + std::to_string(channels)};
    if (bitDepth != 8 && bitDepth != 16) return Error{"PNG encoder: bit depth must be 8 or 16, got " + std::to_string(bitDepth)};
    if (width < 1 || height < 1)
        return Error{"PNG encoder: width and height must be at least 1, got " + std::to_string(width) + "x" +
                     std::to_string(height)};
    for (const auto& [keyword, value] : text) {
        const bool printable = std::all_of(keyword.begin(), keyword.end(), [](char c) { return c >= 32 && c <= 126; });
        if (keyword.empty() || keyword.size() > 79 || !printable || keyword.front() == ' ' || keyword.back() == ' ')
            return Error{"PNG encoder: a tEXt keyword is 1 to 79 printable characters, got '" + keyword + "'"};
    }
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
    for (const auto& [keyword, value] : text) {
        Bytes data(keyword.begin(), keyword.end());
        data.push_back(0);
        data.insert(data.end(), value.begin(), value.end());
        chunk(out, "tEXt", data);
    }
    chunk(out, "IDAT", packed);
    chunk(out, "IEND", {});
    return out;
}

namespace {

// The encoders on one plane each (rows bottom-up), for Buffers and for the images alike.
Result<Bytes> colorPng(int width, int height, const std::uint8_t* rgba) {
    const std::vector<std::uint8_t> rows = flipRows(rgba, width, height, 4);
    return encodePng(width, height, 4, 8, rows.data());
}

Result<Bytes> depthPng(int width, int height, const std::uint32_t* values, DepthFormat format,
                       const std::optional<DepthInfo>& info) {
    std::vector<std::uint16_t> depth16(std::size_t(width) * std::size_t(height));
    const bool reversed = format == DepthFormat::D32F;
    for (std::size_t i = 0; i < depth16.size(); ++i)
        depth16[i] = reversed ? std::uint16_t(std::lround((1.0 - double(windowDepth(format, values[i]))) * 65535.0))
                              : std::uint16_t(values[i] >> 8);
    const std::vector<std::uint8_t> rows =
        flipRows(reinterpret_cast<const std::uint8_t*>(depth16.data()), width, height, 2);
    PngText text;
    if (info) {
        const auto number = [](float v) {
            char s[32];
            std::snprintf(s, sizeof s, "%.9g", double(v));
            return std::string(s);
        };
        text = {
            {"depth_format", depthFormatName(format)},
            {"depth_znear", number(info->znear)},
            {"depth_zfar", info->zfar > 0.0f ? number(info->zfar) : std::string("inf")},
            {"depth_projection", info->perspective ? "perspective" : "orthographic"},
            {"depth_encoding", reversed ? "(1 - window z) * 65535, rounded: 0 near, 65535 far (window z 1 near, 0 far)"
                                        : "the top 16 bits of the 24-bit window z: 0 near, 65535 far"}};
    }
    return encodePng(width, height, 1, 16, rows.data(), text);
}

Bytes depthPfm(int width, int height, const std::uint32_t* values, DepthFormat format) {
    // PFM stores rows bottom-up already, little-endian when the scale is negative.
    const std::string header = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    Bytes out(header.begin(), header.end());
    out.reserve(out.size() + pixels * 4);
    for (std::size_t i = 0; i < pixels; ++i) {
        const float z = windowDepth(format, values[i]);
        std::uint8_t bytes[4];
        std::memcpy(bytes, &z, 4);
        out.insert(out.end(), bytes, bytes + 4);
    }
    return out;
}

Result<Bytes> idPng(int width, int height, const std::uint32_t* ids) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    std::vector<std::uint8_t> bytes(pixels * 4);
    for (std::size_t i = 0; i < pixels; ++i)
        for (int k = 0; k < 4; ++k) bytes[4 * i + k] = std::uint8_t(ids[i] >> (8 * k));
    const std::vector<std::uint8_t> rows = flipRows(bytes.data(), width, height, 4);
    return encodePng(width, height, 4, 8, rows.data());
}

}  // namespace

Result<Bytes> encodeColorPng(const Buffers& b) { return colorPng(b.width, b.height, b.rgba.data()); }
Result<Bytes> encodeDepthPng(const Buffers& b, const std::optional<DepthInfo>& info) {
    return depthPng(b.width, b.height, b.depth.data(), b.depthFormat, info);
}
Bytes encodeDepthPfm(const Buffers& b) { return depthPfm(b.width, b.height, b.depth.data(), b.depthFormat); }
Result<Bytes> encodeIdPng(const Buffers& b) { return idPng(b.width, b.height, b.ids.data()); }

Result<Bytes> encodeColorPng(const ColorImage& image) { return colorPng(image.width, image.height, image.rgba.data()); }
Result<Bytes> encodeDepthPng(const DepthImage& image) {
    return depthPng(image.width, image.height, image.values.data(), image.format,
                    DepthInfo{image.znear, image.zfar, image.perspective});
}
Bytes encodeDepthPfm(const DepthImage& image) {
    return depthPfm(image.width, image.height, image.values.data(), image.format);
}
Result<Bytes> encodeIdPng(const IdImage& image) { return idPng(image.width, image.height, image.ids.data()); }

bool hasExtension(const std::string& path, const std::string& extension) {
    std::string e = std::filesystem::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e == extension;
}

Result<bool> writePng(const std::string& path, const ColorImage& image) {
    return writeFileAtomic(path, encodeColorPng(image));
}
Result<bool> writePng(const std::string& path, const DepthImage& image) {
    return writeFileAtomic(path, encodeDepthPng(image));
}
Result<bool> writePfm(const std::string& path, const DepthImage& image) {
    return writeFileAtomic(path, encodeDepthPfm(image));
}
Result<bool> writePng(const std::string& path, const IdImage& image) {
    return writeFileAtomic(path, encodeIdPng(image));
}

namespace {

// Writes all of `content` to `fd` and closes it: "" or why not, with how far it got.
std::string writeAndClose(int fd, const Content& content) {
    std::uint64_t done = 0;
    const std::uint64_t total = content.size();
    const auto failed = [&](int error) {
        ::close(fd);
        return "write failed after " + std::to_string(done) + " of " + std::to_string(total) +
               " bytes: " + std::strerror(error);
    };
    const auto put = [&](const std::uint8_t* data, std::size_t size) -> std::string {
        std::size_t at = 0;
        while (at < size) {
            // At most 1 GiB a call: Linux writes at most 0x7ffff000 bytes at once anyway.
            const std::size_t chunk = std::min<std::size_t>(size - at, std::size_t(1) << 30);
            const ssize_t n = ::write(fd, data + at, chunk);
            if (n > 0) {
                at += std::size_t(n);
                done += std::uint64_t(n);
            } else if (!(n < 0 && errno == EINTR)) {
                return failed(n < 0 ? errno : EIO);
            }
        }
        return {};
    };
    if (std::string why = put(content.head.data(), content.head.size()); !why.empty()) return why;
    if (content.body) {
        // The body in pieces of 1 MiB, read from its start.
        std::vector<std::uint8_t> piece(std::size_t(1) << 20);
        for (std::uint64_t offset = 0; offset < content.body->size();) {
            const ssize_t n = ::pread(content.body->fd(), piece.data(),
                                      std::size_t(std::min<std::uint64_t>(piece.size(), content.body->size() - offset)),
                                      off_t(offset));
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return failed(n < 0 ? errno : EIO);
            if (std::string why = put(piece.data(), std::size_t(n)); !why.empty()) return why;
            offset += std::uint64_t(n);
        }
    }
    if (std::string why = put(content.tail.data(), content.tail.size()); !why.empty()) return why;
    if (::close(fd) != 0) {  // where a file system reports a full disk late (NFS)
        const int error = errno;
        return "write failed when closing after " + std::to_string(total) + " bytes: " + std::strerror(error);
    }
    return {};
}

// Where `path` is replaced by a renamed file: `path` itself, or, when it is a link, the file the link
// leads to, so that the link stays (/dev/stdout when stdout is a file: /proc/self/fd/1 there).
// Nothing when `path` is, or leads to, a device or a pipe (/dev/null, /dev/full, a terminal, a
// FIFO): that is written in place, since renaming a file over it would replace the device node.
std::optional<std::string> replacedPath(const std::string& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) == 0 && !S_ISREG(status.st_mode) && !S_ISDIR(status.st_mode)) return std::nullopt;
    // Link by link (a dangling link's file is made where it points), at most as many as the kernel follows.
    std::filesystem::path target = path;
    for (int hop = 0; hop < 40 && ::lstat(target.c_str(), &status) == 0 && S_ISLNK(status.st_mode); ++hop) {
        std::error_code error;
        const std::filesystem::path next = std::filesystem::read_symlink(target, error);
        if (error) break;
        target = next.is_absolute() ? next : target.parent_path() / next;
    }
    return target.string();
}

Result<bool> writeInPlace(const std::string& path, const Content& bytes) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) return Error{path + ": cannot write: " + std::strerror(errno), ErrorKind::Io};
    if (std::string why = writeAndClose(fd, bytes); !why.empty()) return Error{path + ": " + why, ErrorKind::Io};
    return true;
}

// Writes `bytes` to a new file beside `target`, named in `temp` before it is created (the caller
// removes it); errors name `path`. O_EXCL: no other writer, in this process or another (even one
// with the same pid in another pid namespace), can share the file, and no link planted at that name
// is followed.
Result<bool> writeTemporary(const std::string& path, const std::string& target, const Content& bytes,
                            std::string& temp) {
    const std::string base = target + ".tmp-" + std::to_string(::getpid());
    constexpr int kNames = 100;
    for (int attempt = 0; attempt < kNames; ++attempt) {
        temp = attempt == 0 ? base : base + "-" + std::to_string(attempt);
        const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) {
            const int error = errno;
            temp.clear();  // not ours to remove
            if (error == EEXIST) continue;
            return Error{path + ": cannot write: " + std::strerror(error), ErrorKind::Io};
        }
        if (std::string why = writeAndClose(fd, bytes); !why.empty()) return Error{path + ": " + why, ErrorKind::Io};
        return true;
    }
    return Error{
        path + ": cannot write: " + std::to_string(kNames) + " temporary names beside it are taken (" + base + ", ...)",
        ErrorKind::Io};
}

}  // namespace

std::optional<std::string> readWholeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

Result<bool> writeFileAtomic(const std::string& path, Result<Content> bytes) {
    OutputSet set;
    set.add(path, std::move(bytes));
    return set.commit();
}

void OutputSet::add(std::string path, Result<Content> content) {
    files_.emplace_back(std::move(path), std::move(content));
}

Result<bool> OutputSet::commit() {
    for (const auto& [path, bytes] : files_)
        if (!bytes) return Error{path + ": cannot encode: " + bytes.error()};

    // Devices and pipes first: what they took cannot be taken back.
    struct Replaced {
        std::size_t file;    // index into files_
        std::string target;  // replacedPath
    };
    std::vector<Replaced> replaced;
    for (std::size_t i = 0; i < files_.size(); ++i) {
        if (std::optional<std::string> target = replacedPath(files_[i].first))
            replaced.push_back({i, std::move(*target)});
        else if (Result<bool> written = writeInPlace(files_[i].first, *files_[i].second); !written) return written;
    }

    // From the first temporary file to the last rename no signal is handled (io/Interrupt.h), and
    // however this returns (an error, an exception), the temporary and backup files it still holds
    // are removed.
    const SignalsHeld held;
    struct Scratch {
        std::vector<std::string> temps, backups;  // by position in `replaced`; "" when there is none
        ~Scratch() {
            for (const std::vector<std::string>* names : {&temps, &backups})
                for (const std::string& name : *names)
                    if (!name.empty()) ::unlink(name.c_str());
        }
    } scratch;
    scratch.temps.resize(replaced.size());
    scratch.backups.resize(replaced.size());
    for (std::size_t k = 0; k < replaced.size(); ++k) {
        const auto& [path, bytes] = files_[replaced[k].file];
        if (Result<bool> written = writeTemporary(path, replaced[k].target, *bytes, scratch.temps[k]); !written)
            return written;
    }

    // Before a file is replaced its old contents get a second name (a hard link: the file itself
    // never disappears), so a later failed rename can put them back. link() fails with ENOENT when
    // another process renames a file over the name meanwhile: then the newer file is the one kept.
    for (std::size_t k = 0; k < replaced.size(); ++k) {
        const std::string& target = replaced[k].target;
        std::string backup = target + ".old-" + std::to_string(::getpid());
        ::unlink(backup.c_str());
        for (int attempt = 0;; ++attempt) {
            struct stat status {};
            if (::lstat(target.c_str(), &status) != 0 || S_ISDIR(status.st_mode)) break;  // nothing to keep
            if (::link(target.c_str(), backup.c_str()) == 0) {
                scratch.backups[k] = std::move(backup);
                break;
            }
            const int error = errno;
            if (error != ENOENT || attempt == 100)
                return Error{files_[replaced[k].file].first +
                                 ": cannot keep the old file while replacing it: " + std::strerror(error),
                             ErrorKind::Io};
        }
    }
    for (std::size_t k = 0; k < replaced.size(); ++k) {
        if (std::rename(scratch.temps[k].c_str(), replaced[k].target.c_str()) == 0) {
            scratch.temps[k].clear();
            continue;
        }
        const int error = errno;
        for (std::size_t j = 0; j < k; ++j) {  // take back what was renamed
            const std::string& earlier = replaced[j].target;
            if (scratch.backups[j].empty()) ::unlink(earlier.c_str());
            else if (std::rename(scratch.backups[j].c_str(), earlier.c_str()) == 0) scratch.backups[j].clear();
        }
        return Error{
            files_[replaced[k].file].first + ": cannot rename the finished file into place: " + std::strerror(error),
            ErrorKind::Io};
    }
    files_.clear();
    return true;
}

namespace {

// stb_image's reason for a failure, for a one-line message. It can quote the file's bytes (an unknown
// chunk's type), which can be control characters or a NUL that ends the text at once.
std::string stbReason() {
    const char* reason = stbi_failure_reason();
    const std::string text = reason ? oneLine(reason) : std::string();
    return text.empty() ? "corrupt data (stb_image gives no readable reason)" : text;
}

}  // namespace

Result<DecodedImage> readPng(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{path + ": cannot open", ErrorKind::Io};
    const std::vector<std::uint8_t> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return decodePng(data, path);
}

Result<DecodedImage> decodePng(std::span<const std::uint8_t> data, const std::string& path) {
    DecodedImage image;
    if (data.size() > std::size_t(INT32_MAX)) return Error{path + ": file too large"};
    const int size = int(data.size());
    int w = 0, h = 0, n = 0;
    if (const Result<ImageSize> checked = checkPng(data); !checked) return Error{path + ": " + checked.error()};
    if (!stbi_info_from_memory(data.data(), size, &w, &h, &n))
        return Error{path + ": not a PNG: " + stbReason()};
    image.width = w;
    image.height = h;
    image.channels = n;
    if (stbi_is_16_bit_from_memory(data.data(), size)) {
        image.bitDepth = 16;
        stbi_us* pixels = stbi_load_16_from_memory(data.data(), size, &w, &h, &n, 0);
        if (!pixels) return Error{path + ": cannot decode: " + stbReason()};
        image.pixels16.assign(pixels, pixels + std::size_t(w) * h * n);
        stbi_image_free(pixels);
    } else {
        stbi_uc* pixels = stbi_load_from_memory(data.data(), size, &w, &h, &n, 0);
        if (!pixels) return Error{path + ": cannot decode: " + stbReason()};
        image.pixels8.assign(pixels, pixels + std::size_t(w) * h * n);
        stbi_image_free(pixels);
    }
    return image;
}

Result<Spool> Spool::create(const std::string& near) {
    std::string folder = std::filesystem::path(near).parent_path().string();
    if (folder.empty()) folder = ".";
    int fd = ::open(folder.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
    if (fd < 0) {  // a file system or a folder without O_TMPFILE: the system's temporary folder
        if (FILE* file = std::tmpfile()) {
            fd = ::dup(::fileno(file));
            std::fclose(file);
        }
    }
    if (fd < 0) return Error{near + ": cannot keep a temporary file: " + std::strerror(errno), ErrorKind::Io};
    return Spool(fd, near);
}

Spool::Spool(Spool&& other) noexcept : fd_(other.fd_), near_(std::move(other.near_)), size_(other.size_) {
    other.fd_ = -1;
}
Spool& Spool::operator=(Spool&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = other.fd_;
        near_ = std::move(other.near_);
        size_ = other.size_;
        other.fd_ = -1;
    }
    return *this;
}
Spool::~Spool() {
    if (fd_ >= 0) ::close(fd_);
}

Result<bool> Spool::append(std::string_view bytes) {
    std::size_t at = 0;
    while (at < bytes.size()) {
        const ssize_t n = ::pwrite(fd_, bytes.data() + at, bytes.size() - at, off_t(size_ + at));
        if (n > 0) {
            at += std::size_t(n);
        } else if (!(n < 0 && errno == EINTR)) {
            const int error = n < 0 ? errno : EIO;
            return Error{near_ + ": write failed after " + std::to_string(size_ + at) +
                             " bytes of its temporary file: " + std::strerror(error),
                         ErrorKind::Io};
        }
    }
    size_ += bytes.size();
    return true;
}

Result<bool> writeFrame(const FramePaths& paths, const Frame& frame) {
    if (!paths.ids.empty() && frame.ids.ids.empty())
        return Error{"ids " + paths.ids + ": the frame has no ids (Settings::ids)"};
    OutputSet files;
    if (!paths.color.empty()) files.add(paths.color, encodeColorPng(frame.color));
    if (!paths.depth.empty())
        files.add(paths.depth, hasExtension(paths.depth, ".pfm") ? Result<Content>(Content(encodeDepthPfm(frame.depth)))
                                                                 : Result<Content>(encodeDepthPng(frame.depth)));
    if (!paths.ids.empty()) files.add(paths.ids, encodeIdPng(frame.ids));
    return files.commit();
}

}  // namespace frugal
