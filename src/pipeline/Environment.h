// An environment map: an equirectangular Radiance .hdr image of the light arriving from every
// direction, prefiltered once when it is loaded into what the shading model reads per pixel
// (pipeline/Backend.h, Lighting::map):
//   - the diffuse light E(n)/π, as nine spherical-harmonic coefficients per channel (bands 0–2, the
//     cosine lobe convolved exactly: Ramamoorthi and Hanrahan 2001), evaluated per pixel at the
//     normal; clamped at 0;
//   - the specular light, kSpecularLevels equirectangular images, level i the map convolved with
//     the GGX lobe of roughness i / (kSpecularLevels − 1) (n = v = r, as the Khronos glTF Sample
//     Renderer prefilters its cube maps: importance-sampled GGX directions weighted by n·l, each read
//     from the level of the source's box pyramid its sample's solid angle covers); read per pixel
//     trilinearly at the reflected view direction and level roughness · (kSpecularLevels − 1).
// Directions: +Y is the image's top row, and a direction d falls at
//   u = 0.5 + atan(d.z, d.x) / 2π,  v = acos(d.y) / π  (v = 0 the top row),
// as the Khronos renderer's panorama-to-cube-map pass reads a panorama. The shaders compute atan and
// acos with the polynomials below (equirectUv), the same in the software reference, instead of
// GLSL's own, whose precision is the driver's.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <frugal/Result.h>

namespace frugal {

// A decoded Radiance image: linear rgb, rows top first.
struct HdrImage {
    int width = 0, height = 0;
    std::vector<float> rgb;  // width · height · 3
};

// The RGBE Radiance format ("#?RADIANCE" or "#?RGBE", FORMAT=32-bit_rle_rgbe, resolution
// "-Y H +X W"), flat or run-length encoded scan lines. Errors name `name` and what is wrong:
// "sky.hdr: not a Radiance file (no #? signature)", "sky.hdr: scan line 12 runs past its 512 pixels".
Result<HdrImage> decodeRadianceHdr(std::span<const std::uint8_t> bytes, const std::string& name);

struct EnvironmentMap {
    static constexpr int kSpecularLevels = 5;          // roughness 0, 0.25, 0.5, 0.75, 1
    static constexpr int kWidth = 512, kHeight = 256;  // level 0; each next level half each side

    std::string source;                     // the file's path
    int sourceWidth = 0, sourceHeight = 0;  // the image's size
    // E(n)/π = max(0, Σ sh[i] · b_i(n)) with b = (1, y, z, x, xy, yz, 3z² − 1, xz, x² − y²): the
    // basis functions' constants and the cosine lobe's band factors are in the coefficients.
    std::array<glm::vec3, 9> sh{};
    struct Level {
        int width = 0, height = 0;
        std::vector<float> rgba;  // width · height · 4, alpha 1, rows top first (v = 0 first)
    };
    std::array<Level, kSpecularLevels> specular;
    double prefilterMs = 0.0;  // what prefiltering took (loadEnvironmentMap: with reading and decoding)
};

// The environment of `image`, prefiltered (on `threads` threads, 0 = every core).
std::shared_ptr<EnvironmentMap> prefilterEnvironment(const HdrImage& image, std::string source, int threads = 0);

// Reads and prefilters `path`, once per path in a process (later calls return the same map).
// Errors: "environment-map PATH: <why>" (not found, not a Radiance file, too large).
Result<std::shared_ptr<const EnvironmentMap>> loadEnvironmentMap(const std::string& path);

// The lookup both backends make: the map's (u, v) of unit direction d, by the polynomial atan and
// acos every shader uses (max error 1e-5 and 7e-5 radians).
glm::vec2 equirectUv(glm::vec3 d);

}  // namespace frugal
