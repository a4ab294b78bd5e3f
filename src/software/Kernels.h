// The hot loops of the software backend, compiled twice from Kernels.inl: once for AVX2 + FMA
// (KernelsAvx2.cpp, chosen at run time when the CPU has both) and once as portable C++
// (KernelsGeneric.cpp, fused or unfused to match what llvmpipe's JIT does on the host). Every
// flavour computes the same bits (Rasterizer.h and Shading.h state the arithmetic); the tests run
// the portable one against the AVX2 one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "pipeline/Brdf.h"
#include "raster/Rasterizer.h"
#include "software/Shading.h"

namespace frugal::sw {

// The backend is written in the rules' own terms (Viewport, Triangle, SetupVertex, ...).
using namespace raster;

// Vertex stage input for vertices [begin, end) of one draw.
struct VertexJob {
    const glm::vec3* positions = nullptr;
    const glm::vec3* normals = nullptr;  // nullptr: (0, 0, 1)
    const glm::vec4* colors = nullptr;   // nullptr: white
    const glm::vec2* uvs = nullptr;      // nullptr: (0, 0)
    const glm::vec4* tangents = nullptr;  // nullptr: no tangent basis (varyings 12–17 are 0)
    glm::mat4 mvp{1.0f};
    glm::mat3 normalMatrix{1.0f};
    glm::mat4 model{1.0f};  // its affine part gives the world position
    glm::mat3 uvTransform{1.0f};
    Viewport viewport;
    SetupVertex* out = nullptr;    // window position, 1/w, varyings
    glm::vec4* clip = nullptr;     // clip-space position
    std::uint8_t* mask = nullptr;  // clip mask
};

// A render target's planes; rows are `stride` pixels apart (stride is a multiple of 8 so that an
// eight-pixel span never reaches into the next row). A multisampled target holds each plane once
// per sample, `sampleStride` values apart (Rasterizer.h, 6.).
struct TargetView {
    std::uint32_t* color = nullptr;  // RGBA8, R in the low byte; nullptr for a linear target
    std::uint32_t* depth = nullptr;  // 24-bit values, or D32F's float bits
    std::uint32_t* ids = nullptr;
    int width = 0, height = 0, stride = 0;
    DepthFormat depthFormat = DepthFormat::D24;
    int samples = 1;
    std::size_t sampleStride = 0;
    float* linear = nullptr;  // RGBA32F (ColorFormat) instead of `color`: 4 floats a pixel (pixel i at 4·i)
};

inline constexpr std::uint32_t kNoWinner = 0xFFFFFFFFu;
// A pixel whose fragment a masked draw discarded (shade() marks it; the pipeline restores its depth
// and id).
inline constexpr std::uint32_t kKilled = 0xFFFFFFFEu;

// One tile being rendered by one thread. Shading is deferred: raster() runs the depth test for every
// triangle of the tile in order, writing depth (and ids, for draws that write them) and recording in
// `winner` which triangle passed last; then shade() runs once per triangle in `won` for the pixels it
// still owns. The result equals shading every fragment that passes, because a fragment's colour
// depends only on its own triangle and pixel. A masked or blended draw's triangle breaks that (its
// depth write depends on its colour; its colour on what is below): the pipeline shades what is
// pending first, then rasterizes and shades that triangle alone (Pipeline.cpp).
struct TileState {
    static constexpr int kPlane = kTileSize * kTileSize;  // one sample's winners
    TargetView target;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the tile's pixels: [x0, x1) × [y0, y1)
    // Per sample (one plane for a single-sampled target): index into `won`, or kNoWinner. The
    // colour of a triangle at a pixel is the same in every sample it wins (the shader runs once per
    // pixel), so shade() shades each pixel once and writes every sample it owns.
    std::uint32_t winner[kMaxSamples * kPlane];
    std::vector<const Triangle*> won;             // triangles that passed the depth test somewhere
    std::vector<std::uint32_t> saved;             // a masked triangle's pixels' depth and ids before it
};

struct Kernels {
    const char* name;
    void (*transform)(const VertexJob& job, std::size_t begin, std::size_t end);
    // Coverage and depth test of one triangle within the tile; records winners.
    void (*raster)(const Triangle& triangle, TileState& tile);
    // Shades the pixels of the tile that `tile.won[index]` still owns. For a masked draw it marks
    // the pixels it discards kKilled in `tile.winner` (and writes no colour there); for a blended
    // one it blends over the target's colour (blendOver; on a linear target blendLinear).
    void (*shade)(std::uint32_t index, const DrawShading& shading, TileState& tile);
};

// The kernels for this CPU: AVX2 when it has AVX2 and FMA and `allowSimd`, else the portable ones,
// fused when the CPU has FMA.
const Kernels& selectKernels(bool allowSimd);

namespace avx2 {
extern const Kernels kKernels;
}
namespace generic {
extern const Kernels kFused;
extern const Kernels kUnfused;
}  // namespace generic

}  // namespace frugal::sw
