// The software Backend: targets, meshes and textures in memory; draws go to the Pipeline
// (Pipeline.h), clears and copies are done here as Mesa performs them (Shading.h).
#include "software/SoftwareBackend.h"

#include <algorithm>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <deque>
#include <new>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>

#include "pipeline/Handles.h"
#include "pipeline/IndexRanges.h"
#include "pipeline/Mipmaps.h"
#include "software/Pipeline.h"
#include "software/Shading.h"

#if !defined(__clang__)  // Clang: -ffp-contract=off (CMakeLists.txt)
#pragma GCC optimize("fp-contract=off")
#endif

namespace frugal {

namespace {

using SwMesh = sw::SoftwareMesh;

// Same limits as the GL backend on llvmpipe (GL_MAX_RENDERBUFFER_SIZE, GL_MAX_TEXTURE_SIZE).
constexpr int kMaxSize = 16384;

// A target's planes, each `samples` times (sample s's at s · plane()).
struct SwTarget {
    int width = 0, height = 0, stride = 0;  // stride: a multiple of 8 (Kernels.h, TargetView)
    int samples = 1;
    std::vector<std::uint32_t> color, depth, ids;  // color: RGBA8 targets only
    std::vector<float> linear;                     // Rgba32F targets: 4 floats a pixel
    DepthFormat depthFormat = DepthFormat::D24;
    ColorFormat colorFormat = ColorFormat::Rgba8;

    std::size_t plane() const { return std::size_t(stride) * std::size_t(height); }
    // Where pixel (x, y) of sample `sample` is in each plane's vector.
    std::size_t at(int sample, int x, int y) const {
        return std::size_t(sample) * plane() + std::size_t(y) * std::size_t(stride) + std::size_t(x);
    }
    sw::TargetView view() {
        return {color.empty() ? nullptr : color.data(),
                depth.data(),
                ids.data(),
                width,
                height,
                stride,
                depthFormat,
                samples,
                plane(),
                linear.empty() ? nullptr : linear.data()};
    }
};

class SoftwareBackend final : public Backend {
public:
    explicit SoftwareBackend(const SoftwareOptions& options)
        : pipeline_(options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency())),
                    options.simd, options.interp) {}

    std::string name() const override { return "software"; }
    std::string renderer() const override {
        // Not Exact: the depth is not llvmpipe's, and the description says so.
        const std::string interp = pipeline_.interp() == span::Interp::Exact
                                       ? ""
                                       : std::string(", ") + toString(pipeline_.interp()) + " depth interpolation";
        return std::string("frugal software rasterizer (llvmpipe rules, ") + pipeline_.kernelName() + " kernels, " +
               std::to_string(pipeline_.threads()) + (pipeline_.threads() == 1 ? " thread" : " threads") + interp + ")";
    }
    const InterpCounters& interpStats() const { return pipeline_.interpStats(); }
    int maxTargetSize() const override { return kMaxSize; }
    int maxSamples() const override { return raster::kMaxSamples; }
    int maxTextureSize() const override { return kMaxSize; }

    // The --interp span engine models a 24-bit depth buffer only.
    bool supportsDepthFormat(DepthFormat format) const override {
        return format == DepthFormat::D24 || pipeline_.interp() == span::Interp::Exact;
    }
    TargetHandle createTarget(int width, int height, DepthFormat format, int samples, ColorFormat color) override;
    void destroyTarget(TargetHandle target) override;
    MeshHandle uploadMesh(const Mesh& mesh) override;
    void releaseMesh(MeshHandle mesh) override;
    bool updateVertices(MeshHandle mesh, std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                        std::span<const glm::vec4> tangents) override;
    void releaseTexture(TextureHandle texture) override;
    TextureHandle uploadTexture(const Texture& texture) override;
    void beginFrame(TargetHandle target, const FrameParams& frame) override;
    void draw(const DrawParams& params, std::span<const IndexRange> ranges) override;
    void clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) override;
    void copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color, bool depth, bool ids) override;
    void readBackInto(TargetHandle target, Buffers& out, Planes planes) override;
    void finish() override { flush(); }
    StateChanges stateChanges() const override { return changes_; }

private:
    // Rasterizes the pending draws (all for frameTarget_).
    void flush() {
        if (!pipeline_.pending()) return;
        SwTarget* target = targets_.find(frameTarget_);
        if (target != nullptr)
            pipeline_.flush(target->view());
        else
            pipeline_.discard();
        // The pending draws' lights (beginFrame) are read no more; the current frame's stay.
        while (lightSets_.size() > 1) lightSets_.pop_front();
        while (environments_.size() > 1) environments_.pop_front();
    }

    sw::Pipeline pipeline_;
    HandleTable<SwTarget, TargetHandle> targets_;
    HandleTable<SwMesh, MeshHandle> meshes_;
    HandleTable<sw::SoftwareTexture, TextureHandle> textures_;

    TargetHandle frameTarget_ = kNoHandle;
    FrameParams frame_;
    // Each frame's punctual lights, kept where a pending draw reads them until it is rasterized (a
    // frame may begin on the same target before the draws of the one before are flushed).
    std::deque<std::vector<FrameLight>> lightSets_;
    std::deque<std::shared_ptr<const EnvironmentMap>> environments_;  // each frame's map, the same way
    StateChanges changes_;  // draws only (no GL state here)
    glm::mat4 viewProjection_{1.0f};
    glm::vec3 eye_{0.0f};  // eyePosition(frame_.view)
};

TargetHandle SoftwareBackend::createTarget(int width, int height, DepthFormat format, int samples, ColorFormat color) {
    if (width <= 0 || height <= 0 || width > kMaxSize || height > kMaxSize) return kNoHandle;
    if (!supportsDepthFormat(format) || samples < 1 || samples > maxSamples()) return kNoHandle;
    // The --interp span engine models one sample per pixel.
    if (samples > 1 && pipeline_.interp() != span::Interp::Exact) return kNoHandle;
    SwTarget t;
    t.width = width;
    t.height = height;
    t.depthFormat = format;
    t.stride = (width + 7) & ~7;
    t.samples = samples > 1 ? raster::kMaxSamples : 1;  // as llvmpipe: 4 for any count it is asked
    const std::size_t pixels = t.plane() * std::size_t(t.samples);
    try {
        // Contents defined from the start, like the GL backend: transparent black, far depth, id 0.
        t.colorFormat = color;
        if (color == ColorFormat::Rgba32F)
            t.linear.assign(pixels * 4, 0.0f);
        else
            t.color.assign(pixels, 0u);
        t.depth.assign(pixels, sw::clearDepthWhole(farDepth(format), format));
        t.ids.assign(pixels, 0u);
    } catch (const std::bad_alloc&) {
        return kNoHandle;
    }
    return targets_.add(std::move(t));
}

void SoftwareBackend::destroyTarget(TargetHandle target) {
    if (targets_.find(target) == nullptr) return;
    if (target == frameTarget_) {
        pipeline_.discard();  // drawn into a target nobody can read any more
        frameTarget_ = kNoHandle;
    }
    targets_.remove(target);
}

MeshHandle SoftwareBackend::uploadMesh(const Mesh& mesh) {
    // The GL backend's validation, so both backends accept and refuse the same meshes.
    if (!isUploadable(mesh)) return kNoHandle;
    const std::size_t vertices = mesh.positions.size();
    const std::size_t triangles = mesh.primitiveCount();
    SwMesh m;
    try {
        m.positions = mesh.positions;
        m.normals = mesh.normals;
        m.colors = mesh.colors;
        m.uvs = mesh.uvs;
        m.tangents = mesh.tangents;
        m.indices = mesh.indices;
        m.triangles = std::uint32_t(triangles);
        m.corners = std::uint32_t(verticesPerPrimitive(mesh.topology));
        m.triangleSource = triangleSources(mesh);
        m.stamp.assign(vertices, 0);
    } catch (const std::bad_alloc&) {
        return kNoHandle;
    }
    return meshes_.add(std::move(m));
}

// Pending draws point into meshes and textures: rasterize them before anything they use goes.
void SoftwareBackend::releaseMesh(MeshHandle mesh) {
    if (meshes_.find(mesh) == nullptr) return;
    flush();
    meshes_.remove(mesh);
}

bool SoftwareBackend::updateVertices(MeshHandle mesh, std::span<const glm::vec3> positions,
                                     std::span<const glm::vec3> normals, std::span<const glm::vec4> tangents) {
    SwMesh* m = meshes_.find(mesh);
    if (m == nullptr || positions.size() != m->positions.size() ||
        (!normals.empty() && normals.size() != m->normals.size()) ||
        (!tangents.empty() && tangents.size() != m->tangents.size()))
        return false;
    flush();  // pending draws were transformed already, but keep the rule of releaseMesh
    std::copy(positions.begin(), positions.end(), m->positions.begin());
    std::copy(normals.begin(), normals.end(), m->normals.begin());
    std::copy(tangents.begin(), tangents.end(), m->tangents.begin());
    return true;
}

void SoftwareBackend::releaseTexture(TextureHandle texture) {
    if (textures_.find(texture) == nullptr) return;
    flush();
    textures_.remove(texture);
}

TextureHandle SoftwareBackend::uploadTexture(const Texture& texture) {
    if (texture.width <= 0 || texture.height <= 0 || texture.width > kMaxSize || texture.height > kMaxSize ||
        texture.rgba.size() != std::size_t(texture.width) * std::size_t(texture.height) * 4)
        return kNoHandle;
    sw::SoftwareTexture t;
    t.filter = texture.filter;
    t.minFilter = texture.minFilter;
    t.mipmaps = texture.mipmaps;
    t.wrapS = texture.wrapS;
    t.wrapT = texture.wrapT;
    const auto simple = [](Wrap w) { return w == Wrap::Repeat || w == Wrap::ClampToEdge; };
    // llvmpipe filters sRGB textures in float, after decoding (Shading.h).
    t.aos = simple(t.wrapS) && simple(t.wrapT) && !texture.srgb;
    t.rgb = texture.srgb ? &sw::srgbDecode(raster::cpuHasFma()) : &sw::unormDecode();
    const auto addLevel = [&t](int width, int height, const std::vector<std::uint8_t>& rgba) {
        sw::SoftwareTexture::Level& level = t.levels.emplace_back();
        level.width = width;
        level.height = height;
        level.texels.resize(std::size_t(width) * std::size_t(height));
        std::memcpy(level.texels.data(), rgba.data(), rgba.size());  // little-endian: R is the low byte
    };
    try {
        addLevel(texture.width, texture.height, texture.rgba);
        if (texture.mipmaps != MipFilter::None)  // the GL backend's levels (pipeline/Mipmaps.h)
            for (const MipLevel& level : mipLevels(texture)) addLevel(level.width, level.height, level.rgba);
    } catch (const std::bad_alloc&) {
        return kNoHandle;
    }
    return textures_.add(std::move(t));
}

void SoftwareBackend::beginFrame(TargetHandle target, const FrameParams& frame) {
    assert(targets_.find(target) != nullptr && "beginFrame: no such target");
    if (targets_.find(target) == nullptr) return;
    assert(targets_.find(target)->depthFormat == frame.depthFormat &&
           "beginFrame: the projection is for another depth format");
    if (target != frameTarget_) flush();
    frameTarget_ = target;
    frame_ = frame;
    // The lights the shading reads: the scene's, or the directional light as the only one.
    std::vector<FrameLight> lights = frame.lighting.lights;
    if (lights.empty()) {
        FrameLight directional;
        directional.direction = -frame.lighting.toLight;
        directional.intensity = glm::vec3(frame.lighting.light);
        lights.push_back(directional);
    }
    if (lightSets_.empty() || lightSets_.back() != lights) lightSets_.push_back(std::move(lights));
    if (environments_.empty() || environments_.back() != frame.lighting.map)
        environments_.push_back(frame.lighting.map);
    viewProjection_ = frame.projection * frame.view;  // as GlBackend::beginFrame, in float with glm
    eye_ = eyePosition(frame.view);
}

void SoftwareBackend::draw(const DrawParams& params, std::span<const IndexRange> ranges) {
    SwTarget* target = targets_.find(frameTarget_);
    SwMesh* mesh = meshes_.find(params.mesh);
    assert(target != nullptr && "draw: no beginFrame, or its target was destroyed");
    assert(mesh != nullptr && "draw: no such mesh");
    if (target == nullptr || mesh == nullptr) return;
    ++changes_.draws;
    sw::DrawInput input;
    input.mvp = viewProjection_ * params.model;  // as GlBackend::draw, in float with glm
    input.normalMatrix = glm::inverseTranspose(glm::mat3(params.model));
    input.model = params.model;
    input.uvTransform = params.uvTransform;
    input.shading.factor = params.baseColorFactor;
    input.shading.metallic = params.metallic;
    input.shading.specular = params.specular;
    input.shading.glossiness = params.glossiness;
    input.shading.roughness = params.roughness;
    // Segments or points without normals: the base colour and the emission, unlit (Backend.h).
    const bool bare = mesh->corners != 3 && mesh->normals.empty() && !params.unlit;
    const bool unlit = params.unlit || bare;
    input.shading.unlit = unlit;
    input.shading.bare = bare;
    input.shading.emission = params.emissive;
    input.shading.eye = eye_;
    const auto texture = [this](TextureHandle handle) -> const sw::SoftwareTexture* {
        if (handle == kNoHandle) return nullptr;
        const sw::SoftwareTexture* t = textures_.find(handle);
        assert(t != nullptr && "draw: no such texture");
        return t;
    };
    input.shading.texture = texture(params.texture);
    input.shading.lambert = frame_.shading == ShadingModel::Lambert && !unlit;
    if (input.shading.lambert || bare) {  // the diffuse term: the base colour's texture and the emission's only
        input.shading.emissive = texture(params.emissiveTexture);
    } else if (!unlit) {  // the other maps are light (as the GL backend's variants)
        input.shading.specularGlossiness = params.specularGlossiness;
        if (params.specularGlossiness)
            input.shading.specularGlossinessMap = texture(params.specularGlossinessTexture);
        else
            input.shading.metallicRoughness = texture(params.metallicRoughnessTexture);
        input.shading.occlusion = texture(params.occlusionTexture);
        input.shading.emissive = texture(params.emissiveTexture);
        input.shading.normalMap = texture(params.normalTexture);
        if (params.clearcoat > 0.0f) {
            input.shading.clearcoat = params.clearcoat;
            input.shading.clearcoatRoughness = params.clearcoatRoughness;
            input.shading.clearcoatNormalScale = params.clearcoatNormalScale;
            input.shading.clearcoatMap = texture(params.clearcoatTexture);
            input.shading.clearcoatRoughnessMap = texture(params.clearcoatRoughnessTexture);
            input.shading.clearcoatNormalMap = texture(params.clearcoatNormalTexture);
        }
    }
    input.shading.normalScale = params.normalScale;
    input.shading.occlusionStrength = params.occlusionStrength;
    input.shading.environment = frame_.lighting.environment;
    input.shading.environmentSpecular = frame_.lighting.environmentSpecular;
    input.shading.environmentMap = unlit ? nullptr : environments_.back().get();
    input.shading.tonemap = frame_.tonemap;
    input.shading.lights = lightSets_.back();  // beginFrame's: frame_'s own may be replaced before a flush
    input.shading.writeIds = frame_.writeIds;
    input.shading.depthTest = params.depth == DepthMode::Test;
    input.shading.alphaMode = params.alphaMode;
    input.shading.alphaCutoff = params.alphaCutoff;
    input.shading.colors = !mesh->colors.empty();
    input.firstId = params.firstId;
    input.doubleSided = params.doubleSided;
    input.depthFormat = target->depthFormat;
    input.samples = target->samples;
    pipeline_.draw(*mesh, target->width, target->height, input, ranges);
}

void SoftwareBackend::clear(TargetHandle target, const Rect& rect, const glm::vec4& color, float depth) {
    SwTarget* t = targets_.find(target);
    assert(t != nullptr && "clear: no such target");
    if (t == nullptr) return;
    flush();
    const Rect r = clipRect(rect, t->width, t->height);
    if (r.empty()) return;
    // Mesa clears the whole target with pipe->clear and a part of it with a quad (Shading.h).
    const bool whole = r.x == 0 && r.y == 0 && r.width == t->width && r.height == t->height;
    const std::uint32_t c = sw::packColor(color);
    const std::uint32_t z = whole ? sw::clearDepthWhole(depth, t->depthFormat)
                                  : sw::clearDepthQuad(depth, pipeline_.fusedViewport(), t->depthFormat);
    // Bands of rows on the pool: a full-HD clear writes 24 MB.
    constexpr int kBand = 64;
    const int bands = (r.height + kBand - 1) / kBand;
    const auto fillBand = [&](std::size_t band, int) {
        const int y0 = r.y + int(band) * kBand, y1 = std::min(y0 + kBand, r.y + r.height);
        for (int sample = 0; sample < t->samples; ++sample)
            for (int y = y0; y < y1; ++y) {
                const std::size_t row = t->at(sample, r.x, y);
                if (t->linear.empty())
                    std::fill_n(t->color.begin() + std::ptrdiff_t(row), r.width, c);
                else
                    for (int x = 0; x < r.width; ++x)  // as given: a float target keeps any value
                        std::memcpy(t->linear.data() + (row + std::size_t(x)) * 4, &color[0], 4 * sizeof(float));
                std::fill_n(t->depth.begin() + std::ptrdiff_t(row), r.width, z);
                std::fill_n(t->ids.begin() + std::ptrdiff_t(row), r.width, 0u);
            }
    };
    if (std::int64_t(r.width) * r.height * t->samples >= 256 * 1024)
        pipeline_.pool().run(std::size_t(bands), fillBand);
    else
        for (int band = 0; band < bands; ++band) fillBand(std::size_t(band), 0);
}

void SoftwareBackend::copy(TargetHandle from, TargetHandle to, const Rect& rect, bool color, bool depth, bool ids) {
    SwTarget* source = targets_.find(from);
    SwTarget* dest = targets_.find(to);
    const std::optional<Rect> region = copyRegion(source, dest, from == to, rect, color || depth || ids);
    if (!region) return;
    const Rect& r = *region;
    flush();
    const auto rows = [&](const std::vector<std::uint32_t>& a, std::vector<std::uint32_t>& b) {
        for (int sample = 0; sample < source->samples; ++sample)
            for (int y = r.y; y < r.y + r.height; ++y)
                std::memcpy(b.data() + dest->at(sample, r.x, y), a.data() + source->at(sample, r.x, y),
                            std::size_t(r.width) * sizeof(std::uint32_t));
    };
    if (color && !source->linear.empty())
        for (int sample = 0; sample < source->samples; ++sample)
            for (int y = r.y; y < r.y + r.height; ++y)
                std::memcpy(dest->linear.data() + dest->at(sample, r.x, y) * 4,
                            source->linear.data() + source->at(sample, r.x, y) * 4,
                            std::size_t(r.width) * 4 * sizeof(float));
    else if (color)
        rows(source->color, dest->color);
    if (depth) rows(source->depth, dest->depth);
    if (ids) rows(source->ids, dest->ids);
}

void SoftwareBackend::readBackInto(TargetHandle target, Buffers& out, Planes planes) {
    SwTarget* t = targets_.find(target);
    assert(t != nullptr && "readBack: no such target");
    if (t == nullptr) {
        out = Buffers{};
        return;
    }
    flush();
    out.width = t->width;
    out.height = t->height;
    out.depthFormat = t->depthFormat;
    const bool linear = !t->linear.empty();
    out.rgba.resize(out.pixelCount() * 4);
    out.linear.resize(linear ? out.pixelCount() * 4 : 0);
    out.depth.resize(planes.depth ? out.pixelCount() : 0);
    out.ids.resize(planes.ids ? out.pixelCount() : 0);
    // Depth and ids: sample 0's (the first plane); colour resolved when multisampled (Shading.h).
    for (int y = 0; y < t->height; ++y) {
        const std::size_t from = t->at(0, 0, y), to = std::size_t(y) * std::size_t(t->width);
        if (linear && t->samples == 1) {
            std::memcpy(out.linear.data() + to * 4, t->linear.data() + from * 4,
                        std::size_t(t->width) * 4 * sizeof(float));
        } else if (linear) {
            for (int x = 0; x < t->width; ++x)
                sw::resolveLinear(t->linear.data() + (from + std::size_t(x)) * 4, t->samples, t->plane(),
                                  out.linear.data() + (to + std::size_t(x)) * 4);
        } else if (t->samples == 1) {
            std::memcpy(out.rgba.data() + to * 4, t->color.data() + from, std::size_t(t->width) * 4);
        } else {
            for (int x = 0; x < t->width; ++x) {
                const std::uint32_t rgba = sw::resolveColor(t->color.data() + from + x, t->samples, t->plane());
                std::memcpy(out.rgba.data() + (to + std::size_t(x)) * 4, &rgba, 4);
            }
        }
        if (planes.depth) std::memcpy(out.depth.data() + to, t->depth.data() + from, std::size_t(t->width) * 4);
        if (planes.depth && t->samples > 1 && t->depthFormat == DepthFormat::D24)
            for (int x = 0; x < t->width; ++x)
                out.depth[to + std::size_t(x)] = sw::resolveDepth24(out.depth[to + std::size_t(x)]);
        if (planes.ids) std::memcpy(out.ids.data() + to, t->ids.data() + from, std::size_t(t->width) * 4);
    }
    if (linear) encodeLinear(out);
}

}  // namespace

std::unique_ptr<Backend> makeSoftwareBackend(const SoftwareOptions& options) {
    return std::make_unique<SoftwareBackend>(options);
}

std::optional<InterpCounters> softwareInterpStats(const Backend& backend) {
    const auto* software = dynamic_cast<const SoftwareBackend*>(&backend);
    if (software == nullptr) return std::nullopt;
    return software->interpStats();
}

}  // namespace frugal
