#include "pipeline/Environment.h"

// equirectUv's arithmetic is what the shaders repeat: every product and sum rounded on its own
// (Clang, which ignores GCC's pragma, is told so by CMakeLists.txt).
#if !defined(__clang__)
#pragma GCC optimize("fp-contract=off")
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

#include "base/Format.h"
#include "base/ThreadPool.h"

namespace frugal {

namespace {

constexpr float kPi = 3.14159265f;
constexpr long long kMaxPixels = 1LL << 26;  // 8192 × 8192
constexpr float kMaxRadiance = 1e30f;        // what prefiltering takes of a texel (resample)

// The header's next line (without its '\n'), or false at the end of the bytes.
bool headerLine(std::span<const std::uint8_t> bytes, std::size_t& at, std::string& line) {
    if (at >= bytes.size()) return false;
    const std::size_t end =
        std::min(bytes.size(),
                 std::size_t(std::find(bytes.begin() + long(at), bytes.end(), std::uint8_t('\n')) - bytes.begin()));
    line.assign(reinterpret_cast<const char*>(bytes.data()) + at, end - at);
    at = end + 1;
    return true;
}

// Radiance's shared-exponent pixel: rgb · 2^(e − 136), 0 where e is 0.
void rgbeToFloat(const std::uint8_t* p, float* out) {
    if (p[3] == 0) {
        out[0] = out[1] = out[2] = 0.0f;
        return;
    }
    const float scale = std::ldexp(1.0f, int(p[3]) - 136);
    for (int c = 0; c < 3; ++c) out[c] = float(p[c]) * scale;
}

}  // namespace

Result<HdrImage> decodeRadianceHdr(std::span<const std::uint8_t> bytes, const std::string& name) {
    const auto bad = [&name](const std::string& why) { return Error{name + ": " + why}; };
    std::size_t at = 0;
    std::string line;
    if (!headerLine(bytes, at, line) || line.rfind("#?", 0) != 0) return bad("not a Radiance file (no #? signature)");
    while (true) {  // a file without FORMAT is RGBE
        if (!headerLine(bytes, at, line)) return bad("the header ends before the image's size");
        if (line.empty()) break;
        if (line.rfind("FORMAT=", 0) == 0 && line != "FORMAT=32-bit_rle_rgbe")
            return bad("format '" + oneLine(line.substr(7), 40) + "' is not 32-bit_rle_rgbe (XYZE is not read)");
    }
    if (!headerLine(bytes, at, line)) return bad("no resolution line");
    char ySign = 0, xSign = 0, yAxis = 0, xAxis = 0;
    long long height = 0, width = 0;
    {
        char tail = 0;
        if (std::sscanf(line.c_str(), "%c%c %lld %c%c %lld%c", &ySign, &yAxis, &height, &xSign, &xAxis, &width,
                        &tail) != 6 ||
            yAxis != 'Y' || xAxis != 'X')
            return bad("resolution '" + oneLine(line, 40) + "' is not '-Y H +X W'");
    }
    if (ySign != '-' || xSign != '+')
        return bad("resolution '" + oneLine(line, 40) +
                   "': only top-to-bottom, left-to-right images (-Y H +X W) are read");
    if (width < 1 || height < 1 || width > kMaxPixels || height > kMaxPixels || width * height > kMaxPixels)
        return bad("size " + std::to_string(width) + "x" + std::to_string(height) + " is not 1 to " +
                   std::to_string(kMaxPixels) + " pixels");

    HdrImage image;
    image.width = int(width);
    image.height = int(height);
    // Grown a scan line at a time: a header may claim more pixels than its data holds.
    std::vector<std::uint8_t> scan(std::size_t(width) * 4);
    const std::size_t w = std::size_t(width);
    for (long long y = 0; y < height; ++y) {
        const std::string row = "scan line " + std::to_string(y);
        const std::size_t left = bytes.size() - std::min(at, bytes.size());
        const bool rle = width >= 8 && width < 32768 && left >= 4 && bytes[at] == 2 && bytes[at + 1] == 2 &&
                         (bytes[at + 2] & 0x80) == 0;
        if (rle) {
            if (((std::size_t(bytes[at + 2]) << 8) | bytes[at + 3]) != w)
                return bad(row + " says it is " + std::to_string((bytes[at + 2] << 8) | bytes[at + 3]) +
                           " pixels wide, not " + std::to_string(width));
            at += 4;
            for (int c = 0; c < 4; ++c) {  // each component's run-length encoded plane
                std::size_t x = 0;
                while (x < w) {
                    if (at >= bytes.size()) return bad("the data ends in " + row);
                    std::size_t count = bytes[at++];
                    const bool run = count > 128;
                    if (run) count -= 128;
                    if (count == 0 || x + count > w)
                        return bad(row + " runs past its " + std::to_string(width) + " pixels");
                    if (run) {
                        if (at >= bytes.size()) return bad("the data ends in " + row);
                        const std::uint8_t v = bytes[at++];
                        for (std::size_t i = 0; i < count; ++i) scan[(x + i) * 4 + std::size_t(c)] = v;
                    } else {
                        if (bytes.size() - at < count) return bad("the data ends in " + row);
                        for (std::size_t i = 0; i < count; ++i) scan[(x + i) * 4 + std::size_t(c)] = bytes[at + i];
                        at += count;
                    }
                    x += count;
                }
            }
        } else {  // flat: four bytes a pixel (the old run-length scheme is not read)
            if (left < w * 4) return bad("the data ends in " + row);
            std::memcpy(scan.data(), bytes.data() + at, w * 4);
            for (std::size_t x = 0; x < w; ++x)
                if (scan[x * 4] == 1 && scan[x * 4 + 1] == 1 && scan[x * 4 + 2] == 1)
                    return bad(row + " uses the old run-length encoding, which is not read");
            at += w * 4;
        }
        image.rgb.resize((std::size_t(y) + 1) * w * 3);
        for (std::size_t x = 0; x < w; ++x) rgbeToFloat(&scan[x * 4], &image.rgb[(std::size_t(y) * w + x) * 3]);
    }
    return image;
}

glm::vec2 equirectUv(glm::vec3 d) {
    // atan(d.z, d.x): a minimax odd polynomial of t = min/max on [0, 1] (error below 1e-5), then the
    // octant's reflections.
    const float ax = std::fabs(d.x), az = std::fabs(d.z);
    const float t = std::min(ax, az) / std::max(std::max(ax, az), 1.0e-30f);
    const float t2 = t * t;
    float a =
        t * (0.99997726f +
             t2 * (-0.33262347f + t2 * (0.19354346f + t2 * (-0.11643287f + t2 * (0.05265332f + t2 * -0.01172120f)))));
    if (az > ax) a = 1.57079633f - a;
    if (d.x < 0.0f) a = kPi - a;
    if (d.z < 0.0f) a = -a;
    // acos(d.y): Abramowitz and Stegun 4.4.45 (error below 7e-5).
    const float ay = std::min(std::fabs(d.y), 1.0f);
    float c = std::sqrt(1.0f - ay) * (1.5707288f + ay * (-0.2121144f + ay * (0.0742610f + ay * -0.0187293f)));
    if (d.y < 0.0f) c = kPi - c;
    return {0.5f + a * (0.5f / kPi), c * (1.0f / kPi)};
}

namespace {

// A float rgb image, sampled bilinearly: u wraps, v is clamped (an equirectangular map).
struct Plane {
    int width = 0, height = 0;
    std::vector<glm::vec3> texels;

    glm::vec3 at(int x, int y) const {
        x = ((x % width) + width) % width;
        y = std::clamp(y, 0, height - 1);
        return texels[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    }
    glm::vec3 bilinear(glm::vec2 uv) const {
        const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
        const float fx = std::floor(x), fy = std::floor(y);
        const int x0 = int(fx), y0 = int(fy);
        const float wx = x - fx, wy = y - fy;
        const glm::vec3 top = at(x0, y0) * (1.0f - wx) + at(x0 + 1, y0) * wx;
        const glm::vec3 bottom = at(x0, y0 + 1) * (1.0f - wx) + at(x0 + 1, y0 + 1) * wx;
        return top * (1.0f - wy) + bottom * wy;
    }
    // Half each side (at least 1), each texel the mean of the ones it covers.
    Plane half() const {
        Plane out;
        out.width = std::max(1, width / 2);
        out.height = std::max(1, height / 2);
        out.texels.resize(std::size_t(out.width) * std::size_t(out.height));
        const int sx = width / out.width, sy = height / out.height;
        for (int y = 0; y < out.height; ++y)
            for (int x = 0; x < out.width; ++x) {
                glm::vec3 sum(0.0f);
                for (int j = 0; j < sy; ++j)
                    for (int i = 0; i < sx; ++i) sum += at(x * sx + i, y * sy + j);
                out.texels[std::size_t(y) * std::size_t(out.width) + std::size_t(x)] = sum / float(sx * sy);
            }
        return out;
    }
};

// The unit direction of (u, v) on the map (equirectUv's inverse).
glm::vec3 direction(float u, float v) {
    const float phi = (u - 0.5f) * 2.0f * kPi, theta = v * kPi;
    return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

// `image` resampled to width × height: each texel the mean of the source texels whose centres fall
// in it, or the bilinear sample at its centre where none does. A value that is not finite or below
// 0 counts as 0, and one above kMaxRadiance as that (RGBE reaches 1.7e38: sums of such overflow).
Plane resample(const HdrImage& image, int width, int height) {
    Plane source{image.width, image.height, {}};
    source.texels.resize(std::size_t(image.width) * std::size_t(image.height));
    for (std::size_t i = 0; i < source.texels.size(); ++i) {
        glm::vec3 c(image.rgb[i * 3], image.rgb[i * 3 + 1], image.rgb[i * 3 + 2]);
        for (int k = 0; k < 3; ++k) c[k] = std::isfinite(c[k]) ? std::clamp(c[k], 0.0f, kMaxRadiance) : 0.0f;
        source.texels[i] = c;
    }
    Plane out{width, height, std::vector<glm::vec3>(std::size_t(width) * std::size_t(height))};
    for (int y = 0; y < height; ++y) {
        const int y0 = int(std::ceil(float(y) * float(image.height) / float(height) - 0.5f));
        const int y1 = int(std::ceil(float(y + 1) * float(image.height) / float(height) - 0.5f));
        for (int x = 0; x < width; ++x) {
            const int x0 = int(std::ceil(float(x) * float(image.width) / float(width) - 0.5f));
            const int x1 = int(std::ceil(float(x + 1) * float(image.width) / float(width) - 0.5f));
            glm::vec3 sum(0.0f);
            int n = 0;
            for (int j = std::max(y0, 0); j < std::min(y1, image.height); ++j)
                for (int i = std::max(x0, 0); i < std::min(x1, image.width); ++i, ++n) sum += source.at(i, j);
            out.texels[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                n > 0 ? sum / float(n)
                      : source.bilinear({(float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height)});
        }
    }
    return out;
}

float radicalInverse(std::uint32_t bits) {
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    return float(bits) * 2.3283064365386963e-10f;
}

}  // namespace

std::shared_ptr<EnvironmentMap> prefilterEnvironment(const HdrImage& image, std::string source, int threads) {
    const auto start = std::chrono::steady_clock::now();
    auto map = std::make_shared<EnvironmentMap>();
    map->source = std::move(source);
    map->sourceWidth = image.width;
    map->sourceHeight = image.height;
    constexpr int W = EnvironmentMap::kWidth, H = EnvironmentMap::kHeight, kLevels = EnvironmentMap::kSpecularLevels;
    std::vector<Plane> pyramid{resample(image, W, H)};
    while (pyramid.back().width > 4) pyramid.push_back(pyramid.back().half());

    // The diffuse light: the base level projected on the nine basis functions (solid-angle weighted),
    // times each band's cosine-lobe factor / π and the basis constant squared.
    const Plane& base = pyramid[0];
    std::array<glm::dvec3, 9> sum{};
    for (int y = 0; y < H; ++y) {
        const double theta = (double(y) + 0.5) / H * 3.14159265358979;
        const double weight = (2.0 * 3.14159265358979 / W) * (3.14159265358979 / H) * std::sin(theta);
        for (int x = 0; x < W; ++x) {
            const glm::vec3 d = direction((float(x) + 0.5f) / float(W), (float(y) + 0.5f) / float(H));
            const double b[9] = {
                1.0, d.y, d.z, d.x, d.x * d.y, d.y * d.z, 3.0 * d.z * d.z - 1.0, d.x * d.z, d.x * d.x - d.y * d.y};
            const glm::dvec3 l = glm::dvec3(base.texels[std::size_t(y) * W + std::size_t(x)]) * weight;
            for (int i = 0; i < 9; ++i) sum[std::size_t(i)] += l * b[i];
        }
    }
    const double k[9] = {0.282095, 0.488603, 0.488603, 0.488603, 1.092548, 1.092548, 0.315392, 1.092548, 0.546274};
    const double band[9] = {1.0, 2.0 / 3, 2.0 / 3, 2.0 / 3, 0.25, 0.25, 0.25, 0.25, 0.25};
    for (int i = 0; i < 9; ++i) map->sh[std::size_t(i)] = glm::vec3(sum[std::size_t(i)] * (band[i] * k[i] * k[i]));

    // The specular levels: level 0 the map itself, level i the GGX lobe of roughness i / (levels − 1)
    // around n = v = r, importance-sampled (Hammersley points), each sample weighted by n·l and read
    // from the pyramid level its solid angle covers.
    constexpr int kSamples = 256;
    const double texelAngle = 4.0 * 3.14159265358979 / (double(W) * H);
    ThreadPool pool(threads > 0 ? threads : int(std::max(1u, std::thread::hardware_concurrency())));
    for (int level = 0; level < kLevels; ++level) {
        EnvironmentMap::Level& out = map->specular[std::size_t(level)];
        out.width = W >> level;
        out.height = H >> level;
        out.rgba.assign(std::size_t(out.width) * std::size_t(out.height) * 4, 1.0f);
        const float roughness = float(level) / float(kLevels - 1);
        const float alpha = roughness * roughness, alpha2 = alpha * alpha;
        const Plane* plane = level == 0 ? &base : nullptr;
        pool.run(std::size_t(out.height), [&](std::size_t y, int) {
            for (int x = 0; x < out.width; ++x) {
                glm::vec3 c;
                const glm::vec2 uv((float(x) + 0.5f) / float(out.width), (float(y) + 0.5f) / float(out.height));
                if (plane) {
                    c = plane->texels[y * std::size_t(W) + std::size_t(x)];
                } else {
                    const glm::vec3 n = direction(uv.x, uv.y);
                    const glm::vec3 up = std::fabs(n.y) < 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
                    const glm::vec3 tx = glm::normalize(glm::cross(up, n)), ty = glm::cross(n, tx);
                    glm::dvec3 acc(0.0);
                    double weights = 0.0;
                    for (int s = 0; s < kSamples; ++s) {
                        const float e1 = (float(s) + 0.5f) / kSamples, e2 = radicalInverse(std::uint32_t(s));
                        const float cosH = std::sqrt((1.0f - e1) / (1.0f + (alpha2 - 1.0f) * e1));
                        const float sinH = std::sqrt(std::max(0.0f, 1.0f - cosH * cosH)), phi = 2.0f * kPi * e2;
                        const glm::vec3 h = tx * (sinH * std::cos(phi)) + ty * (sinH * std::sin(phi)) + n * cosH;
                        const glm::vec3 l = h * (2.0f * cosH) - n;
                        const float nl = glm::dot(n, l);
                        if (nl <= 0.0f) continue;
                        const float f = cosH * cosH * (alpha2 - 1.0f) + 1.0f;
                        const double pdf = alpha2 / (kPi * f * f) / 4.0;  // D(h)·(n·h) / (4·v·h), v = n
                        const double lod = std::clamp(0.5 * std::log2(1.0 / (kSamples * pdf) / texelAngle), 0.0,
                                                      double(pyramid.size() - 1));
                        const int l0 = int(lod);
                        const int l1 = std::min(l0 + 1, int(pyramid.size()) - 1);
                        const float t = float(lod - l0);
                        const glm::vec2 at = equirectUv(glm::normalize(l));
                        const glm::vec3 sample = pyramid[std::size_t(l0)].bilinear(at) * (1.0f - t) +
                                                 pyramid[std::size_t(l1)].bilinear(at) * t;
                        acc += glm::dvec3(sample) * double(nl);
                        weights += nl;
                    }
                    c = weights > 0.0 ? glm::vec3(acc / weights) : glm::vec3(0.0f);
                }
                float* texel = &out.rgba[(y * std::size_t(out.width) + std::size_t(x)) * 4];
                texel[0] = c.r;
                texel[1] = c.g;
                texel[2] = c.b;
            }
        });
    }
    map->prefilterMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return map;
}

Result<std::shared_ptr<const EnvironmentMap>> loadEnvironmentMap(const std::string& path) {
    static std::mutex mutex;
    static std::map<std::string, std::shared_ptr<const EnvironmentMap>> loaded;
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = loaded.find(path); it != loaded.end()) return it->second;
    const std::string name = "environment-map " + path;
    const auto start = std::chrono::steady_clock::now();
    std::ifstream in(path, std::ios::binary);
    if (!in) return Error{name + ": cannot open it (" + std::strerror(errno) + ")"};
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) return Error{name + ": cannot read it"};
    Result<HdrImage> image = decodeRadianceHdr(bytes, name);
    if (!image) return image.error();
    std::shared_ptr<EnvironmentMap> map = prefilterEnvironment(*image, path);
    map->prefilterMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    loaded.emplace(path, map);
    return std::shared_ptr<const EnvironmentMap>(std::move(map));
}

}  // namespace frugal
