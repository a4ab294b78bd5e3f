// The GL backend's draws: beginFrame, draw and drawInstances, the id pass's expanded vertex
// buffers, and many short ranges gathered into one index buffer (the class: GlBackendImpl.h).
//
// Vertex arithmetic (the software reference repeats it exactly, in float, with glm):
//   u_mvp = (projection * view) * model       (projection * view computed once per frame)
//   u_normalMatrix = transpose(inverse(mat3(model)))
//   gl_Position = u_mvp * vec4(position, 1)
//
// Triangle ids: reading gl_PrimitiveID in the fragment stage is slower on llvmpipe than a flat
// vertex attribute (docs/gl/README.md), so a frame that writes ids draws each mesh unindexed from an
// "expanded" vertex buffer: 3 vertices per triangle, in the mesh's triangle order, each carrying the
// flat attribute triangleSource[t]. It is built on the first draw of the mesh with ids, from the
// mesh's own GL buffers (read back once, so no CPU copy of every mesh is kept for a pass that may
// never run). Ranges become glMultiDrawArrays over [3·first, 3·count). Without ids the mesh is drawn
// indexed (glMultiDrawElements) into colour attachment 0 only, and the id attachment keeps what it
// holds. Both paths run the same arithmetic on the same vertex values, so colour and depth are
// identical.
//
// Many short ranges (a culled plan: a thousand runs or more, of a few tens of triangles each) are
// gathered into one index buffer streamed for the draw (glBufferData, GL_STREAM_DRAW) and drawn with
// one glDrawElements: the same triangles in the same order, so the same pixels. llvmpipe runs each
// range of a glMultiDrawElements as a draw of its own, and one index buffer draws a culled plan's
// ranges faster (docs/gl/README.md); kGatherMinRuns and kGatherMaxAverageRun say when a draw is
// gathered. The mesh's indices are read back from its buffer once, on the first gathered draw (no
// CPU copy is kept for meshes never culled).
#include <algorithm>
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/GlApi.h"
#include "gl/GlBackendImpl.h"
#include "pipeline/IndexRanges.h"

namespace frugal::gl {

namespace {

// A draw's ranges are gathered into one streamed index buffer when there are at least this many and
// they are this short on average (triangles); otherwise glMultiDrawElements takes them as they are.
constexpr std::size_t kGatherMinRuns = 64;
constexpr std::size_t kGatherMaxAverageRun = 256;

}  // namespace

// (Frames that write ids draw every range on its own: the id pass is not gathered.)
RangeGathering GlBackend::rangeGathering() const { return {kGatherMinRuns, kGatherMaxAverageRun}; }

void GlBackend::beginFrame(TargetHandle target, const FrameParams& frame) {
    assert(targets_.find(target) != nullptr && "beginFrame: no such target");
    if (targets_.find(target) == nullptr) return;
    assert(targets_.find(target)->depthFormat == frame.depthFormat &&
           "beginFrame: the projection is for another depth format");
    frameTarget_ = target;
    frame_ = frame;
    // The lighting goes to each program on its first draw of the frame (uniforms are per program).
    viewProjection_ = frame.projection * frame.view;
    eye_ = eyePosition(frame.view);
    lights_ = {};
    const std::size_t count = std::min(frame.lighting.lights.size(), std::size_t(kMaxLights));
    for (std::size_t i = 0; i < count; ++i) {
        const FrameLight& l = frame.lighting.lights[i];
        lights_[4 * i] = glm::vec4(l.position, float(l.type));
        lights_[4 * i + 1] = glm::vec4(l.direction, l.range);
        lights_[4 * i + 2] = glm::vec4(l.intensity, l.outerCos);
        lights_[4 * i + 3] = glm::vec4(l.innerCos, 0.0f, 0.0f, 0.0f);
    }
    lights_[4 * kMaxLights] = glm::vec4(float(count), 0.0f, 0.0f, 0.0f);
    if (frame.lighting.map && frame.lighting.map != environment_) {  // kept across frames without a map
        uploadEnvironment(*frame.lighting.map);
        environment_ = frame.lighting.map;
    }
}

void GlBackend::uploadEnvironment(const EnvironmentMap& map) {
    if (environmentTexture_ == 0) gl_.GenTextures(1, &environmentTexture_);
    state_.bindTexture(environmentTexture_, kEnvironmentUnit);
    for (int level = 0; level < EnvironmentMap::kSpecularLevels; ++level) {
        const EnvironmentMap::Level& l = map.specular[std::size_t(level)];
        gl_.TexImage2D(GL_TEXTURE_2D, level, GL_RGBA32F, l.width, l.height, 0, GL_RGBA, GL_FLOAT, l.rgba.data());
    }
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, EnvironmentMap::kSpecularLevels - 1);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

GlProgram* GlBackend::prepareDraw(const DrawParams& params, GlTarget& target, const GlMesh& mesh, unsigned extraBits) {
    const bool writeIds = frame_.writeIds;
    // The variant: each map, vertex colours and ids only when the draw uses them.
    unsigned variant = (writeIds ? kIdsBit : 0u) | extraBits;
    const std::pair<TextureHandle, unsigned> maps[kTextureUnits] = {
        {params.texture, kTextureBit},
        {params.metallicRoughnessTexture, kMetallicRoughnessBit},
        {params.occlusionTexture, kOcclusionBit},
        {params.emissiveTexture, kEmissiveBit},
        {params.normalTexture, kNormalMapBit},
        {params.specularGlossinessTexture, kSpecularGlossinessMapBit},
        {params.clearcoatTexture, kClearcoatMapBit},
        {params.clearcoatRoughnessTexture, kClearcoatRoughnessMapBit},
        {params.clearcoatNormalTexture, kClearcoatNormalMapBit}};
    GLuint textures[kTextureUnits] = {};
    for (int unit = 0; unit < kTextureUnits; ++unit) {
        if (maps[unit].first == kNoHandle) continue;
        const GLuint* t = textures_.find(maps[unit].first);
        assert(t != nullptr && "draw: no such texture");
        if (t) {
            textures[unit] = *t;
            variant |= maps[unit].second;
        }
    }
    if (params.specularGlossiness) variant = (variant & ~kMetallicRoughnessBit) | kSpecularGlossinessBit;
    else variant &= ~kSpecularGlossinessMapBit;
    if (params.clearcoat > 0.0f) variant |= kClearcoatBit;
    else variant &= ~kClearcoatBits;
    // Segments or points without normals: the base colour and the emission, unlit (Backend.h).
    const bool bare = mesh.mode != GL_TRIANGLES && mesh.layout.normal < 0 && !params.unlit;
    if (params.unlit || bare)  // light only (a bare draw keeps its emissive map)
        variant &= ~(kMetallicRoughnessBit | kOcclusionBit | (bare ? 0u : kEmissiveBit) | kNormalMapBit |
                     kSpecularGlossinessBit | kSpecularGlossinessMapBit | kClearcoatBits);
    if (bare) variant |= kBareBit;
    const bool unlit = params.unlit || bare;
    if (frame_.shading == ShadingModel::Lambert && !unlit)  // the diffuse term: base colour and emission
        variant = (variant & ~(kMetallicRoughnessBit | kOcclusionBit | kNormalMapBit | kSpecularGlossinessBit |
                               kSpecularGlossinessMapBit | kClearcoatBit | kClearcoatBits)) |
                  kLambertBit;
    if (mesh.layout.tangent < 0) variant &= ~(kNormalMapBit | kClearcoatNormalMapBit);  // no basis to read them in
    if (mesh.layout.color >= 0) variant |= kColorsBit;
    if (unlit) variant |= kUnlitBit;
    if (params.alphaMode == AlphaMode::Mask) variant |= kAlphaMaskBit;
    if (params.alphaMode == AlphaMode::Blend) variant |= kAlphaBlendBit;
    if (frame_.tonemap == ToneMap::PbrNeutral) variant |= kToneMapNeutralBit;
    if (frame_.tonemap == ToneMap::Aces) variant |= kToneMapAcesBit;
    if (!unlit && !frame_.lighting.lights.empty()) variant |= kLightsBit;
    if (!unlit && frame_.lighting.map) variant |= kEnvironmentMapBit;
    if (!unlit && frame_.shading == ShadingModel::Full && !frame_.lighting.environmentSpecular)
        variant |= kNoEnvironmentSpecularBit;
    if (target.colorFormat == ColorFormat::Rgba32F) variant |= kLinearBit;
    if (!unlit && !(variant & kLambertBit)) {  // one side of the metal mix alone (Backend.h)
        const MetalMix mix = metalMixOf(params.metallic, (variant & kMetallicRoughnessBit) != 0,
                                        (variant & kSpecularGlossinessBit) != 0);
        if (mix == MetalMix::Dielectric) variant |= kDielectricBit;
        if (mix == MetalMix::Metal) variant |= kMetalBit;
    }
    GlProgram* p = program(variant);
    if (p == nullptr) return nullptr;

    state_.drawInto(target, writeIds ? DrawSet::ColorAndIds : DrawSet::Color);
    state_.setViewport(target.width, target.height);
    state_.setScissor(false);
    state_.setCull(!params.doubleSided);
    state_.setDepthTest(params.depth == DepthMode::Test);
    state_.setBlend(params.alphaMode == AlphaMode::Blend);
    state_.setDepthConvention(target.depthFormat);
    for (int unit = 0; unit < kTextureUnits; ++unit)
        if (variant & maps[unit].second) state_.bindTexture(textures[unit], unit);

    const Lighting& light = frame_.lighting;
    if (state_.uniformChanged(p->eyeValue, eye_)) gl_.Uniform3fv(p->eye, 1, glm::value_ptr(eye_));
    if (state_.uniformChanged(p->toLightValue, light.toLight))
        gl_.Uniform3fv(p->toLight, 1, glm::value_ptr(light.toLight));
    if (state_.uniformChanged(p->lightValue, light.light)) gl_.Uniform1f(p->light, light.light);
    if (state_.uniformChanged(p->environmentValue, light.environment))
        gl_.Uniform1f(p->environment, light.environment);
    if ((variant & kLightsBit) && state_.uniformChanged(p->lightsValue, lights_))
        gl_.Uniform4fv(p->lights, GLsizei(lights_.size()), glm::value_ptr(lights_[0]));
    if (variant & kEnvironmentMapBit) {
        state_.bindTexture(environmentTexture_, kEnvironmentUnit);
        const std::array<glm::vec3, 9>& sh = frame_.lighting.map->sh;  // environment_'s (beginFrame)
        if (state_.uniformChanged(p->environmentShValue, sh))
            gl_.Uniform3fv(p->environmentSh, 9, glm::value_ptr(sh[0]));
    }
    // The material: the same for every instance of a batched draw.
    if (state_.uniformChanged(p->baseColorFactorValue, params.baseColorFactor))
        gl_.Uniform4fv(p->baseColorFactor, 1, glm::value_ptr(params.baseColorFactor));
    if ((variant & kMapBits) && state_.uniformChanged(p->uvTransformValue, params.uvTransform))
        gl_.UniformMatrix3fv(p->uvTransform, 1, GL_FALSE, glm::value_ptr(params.uvTransform));
    if ((variant & kOcclusionBit) && state_.uniformChanged(p->occlusionStrengthValue, params.occlusionStrength))
        gl_.Uniform1f(p->occlusionStrength, params.occlusionStrength);
    if ((variant & kNormalMapBit) && state_.uniformChanged(p->normalScaleValue, params.normalScale))
        gl_.Uniform1f(p->normalScale, params.normalScale);
    if ((!params.unlit || bare) && state_.uniformChanged(p->emissiveValue, params.emissive))
        gl_.Uniform3fv(p->emissive, 1, glm::value_ptr(params.emissive));
    if ((variant & kAlphaMaskBit) && state_.uniformChanged(p->alphaCutoffValue, params.alphaCutoff))
        gl_.Uniform1f(p->alphaCutoff, params.alphaCutoff);
    const glm::vec4 specularGlossiness(params.specular, params.glossiness);
    if ((variant & kSpecularGlossinessBit) && state_.uniformChanged(p->specularGlossinessValue, specularGlossiness))
        gl_.Uniform4fv(p->specularGlossiness, 1, glm::value_ptr(specularGlossiness));
    const glm::vec3 clearcoat(params.clearcoat, params.clearcoatRoughness, params.clearcoatNormalScale);
    if ((variant & kClearcoatBit) && state_.uniformChanged(p->clearcoatValue, clearcoat))
        gl_.Uniform3fv(p->clearcoat, 1, glm::value_ptr(clearcoat));
    const glm::vec2 metallicRoughness(params.metallic, params.roughness);
    if (state_.uniformChanged(p->metallicRoughnessValue, metallicRoughness))
        gl_.Uniform2fv(p->metallicRoughness, 1, glm::value_ptr(metallicRoughness));

    // Attributes the mesh lacks read the current generic value. That value is context state, and
    // GL 3.3 leaves it undefined after a draw that sourced the attribute from an array, so it is
    // set before every draw that needs it: normal +z, uv (0,0). (Colours and ids are only in the
    // variants of meshes that have them.)
    if (mesh.layout.normal < 0) gl_.VertexAttrib3f(kNormal, 0.0f, 0.0f, 1.0f);
    if ((variant & kMapBits) && mesh.layout.uv < 0) gl_.VertexAttrib2f(kUv, 0.0f, 0.0f);
    return p;
}

void GlBackend::draw(const DrawParams& params, std::span<const IndexRange> ranges) {
    GlTarget* target = targets_.find(frameTarget_);
    GlMesh* mesh = meshes_.find(params.mesh);
    assert(target != nullptr && "draw: no beginFrame, or its target was destroyed");
    assert(mesh != nullptr && "draw: no such mesh");
    if (target == nullptr || mesh == nullptr) return;

    const std::uint64_t triangles = normalizeRanges(ranges, mesh->triangles, runs_);
    if (triangles == 0) return;
    counts_.clear();
    firsts_.clear();
    for (const IndexRange& run : runs_) {
        firsts_.push_back(GLint(run.firstTriangle));
        counts_.push_back(GLsizei(run.triangleCount));
    }

    activate();
    const bool writeIds = frame_.writeIds;
    GlProgram* p = prepareDraw(params, *target, *mesh, 0u);
    if (p == nullptr) return;
    const glm::mat4 mvp = viewProjection_ * params.model;
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(params.model));
    if (state_.uniformChanged(p->mvpValue, mvp)) gl_.UniformMatrix4fv(p->mvp, 1, GL_FALSE, glm::value_ptr(mvp));
    if (state_.uniformChanged(p->normalMatrixValue, normalMatrix))
        gl_.UniformMatrix3fv(p->normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
    if (state_.uniformChanged(p->modelValue, params.model))
        gl_.UniformMatrix4fv(p->model, 1, GL_FALSE, glm::value_ptr(params.model));
    if (writeIds && state_.uniformChanged(p->firstIdValue, params.firstId)) gl_.Uniform1ui(p->firstId, params.firstId);
    state_.countDraw();

    if (writeIds) {
        target->idsDirty = true;
        if (mesh->idVao == 0 && !buildIdPass(*mesh)) {
            assert(false && "draw: could not build the id pass (out of memory?)");
            return;
        }
        for (std::size_t i = 0; i < counts_.size(); ++i) {
            firsts_[i] *= GLint(mesh->corners);
            counts_[i] *= GLsizei(mesh->corners);
        }
        state_.bindVao(mesh->idVao);
        gl_.MultiDrawArrays(mesh->mode, firsts_.data(), counts_.data(), GLsizei(counts_.size()));
    } else if (runs_.size() >= kGatherMinRuns &&
               triangles / runs_.size() < kGatherMaxAverageRun) {
        drawGathered(*mesh, triangles);
    } else {
        offsets_.resize(counts_.size());
        for (std::size_t i = 0; i < counts_.size(); ++i) {
            offsets_[i] =
                reinterpret_cast<const void*>(std::uintptr_t(firsts_[i]) * mesh->corners * sizeof(std::uint32_t));
            counts_[i] *= GLsizei(mesh->corners);
        }
        state_.bindVao(mesh->vao);
        gl_.MultiDrawElements(mesh->mode, counts_.data(), GL_UNSIGNED_INT, offsets_.data(), GLsizei(counts_.size()));
    }
    check("draw");
}

void GlBackend::drawGathered(GlMesh& m, std::uint64_t triangles) {
    if (m.indices.empty()) {
        m.indices.resize(std::size_t(m.triangles) * m.corners);
        readBuffer(m.ibo, m.indices.data(), GLsizeiptr(m.indices.size() * sizeof(std::uint32_t)));
    }
    gathered_.resize(std::size_t(triangles) * m.corners);
    std::uint32_t* out = gathered_.data();
    for (const IndexRange& run : runs_) {
        const std::uint32_t* from = m.indices.data() + std::size_t(run.firstTriangle) * m.corners;
        out = std::copy(from, from + std::size_t(run.triangleCount) * m.corners, out);
    }
    if (streamIbo_ == 0) gl_.GenBuffers(1, &streamIbo_);
    // The element binding is VAO state: the stream buffer goes into the mesh's VAO for this draw and
    // the mesh's own index buffer comes back after it.
    state_.bindVao(m.vao);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, streamIbo_);
    gl_.BufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(gathered_.size() * sizeof(std::uint32_t)), gathered_.data(),
                   GL_STREAM_DRAW);
    gl_.DrawElements(m.mode, GLsizei(gathered_.size()), GL_UNSIGNED_INT, nullptr);
    gl_.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.ibo);
}

bool GlBackend::buildIdPass(GlMesh& m) {
    std::vector<std::uint8_t> vertexData(static_cast<std::size_t>(m.layout.size));
    std::vector<std::uint32_t> indices(std::size_t(m.triangles) * m.corners);
    readBuffer(m.vbo, vertexData.data(), m.layout.size);
    readBuffer(m.ibo, indices.data(), GLsizeiptr(indices.size() * sizeof(std::uint32_t)));

    // Same sections as the indexed buffer, 3 vertices per triangle (2 a segment, 1 a point), plus the
    // id section.
    const std::size_t n = indices.size();
    VertexLayout expanded;
    GLsizeiptr size = GLsizeiptr(n * sizeof(glm::vec3));
    const auto section = [&size, n](GLintptr source, std::size_t elementSize) -> GLintptr {
        if (source < 0) return -1;
        const GLintptr at = size;
        size += GLsizeiptr(n * elementSize);
        return at;
    };
    expanded.normal = section(m.layout.normal, sizeof(glm::vec3));
    expanded.color = section(m.layout.color, sizeof(glm::vec4));
    expanded.uv = section(m.layout.uv, sizeof(glm::vec2));
    expanded.tangent = section(m.layout.tangent, sizeof(glm::vec4));
    expanded.id = section(0, sizeof(std::uint32_t));
    expanded.size = size;
    m.idLayout = expanded;
    std::vector<std::uint8_t> data(static_cast<std::size_t>(size));
    const auto gather = [&](GLintptr from, GLintptr to, std::size_t elementSize) {
        if (from < 0) return;
        for (std::size_t k = 0; k < n; ++k)
            std::memcpy(data.data() + to + k * elementSize, vertexData.data() + from + indices[k] * elementSize,
                        elementSize);
    };
    gather(0, 0, sizeof(glm::vec3));
    gather(m.layout.normal, expanded.normal, sizeof(glm::vec3));
    gather(m.layout.color, expanded.color, sizeof(glm::vec4));
    gather(m.layout.uv, expanded.uv, sizeof(glm::vec2));
    gather(m.layout.tangent, expanded.tangent, sizeof(glm::vec4));
    for (std::size_t k = 0; k < n; ++k)
        std::memcpy(data.data() + expanded.id + k * sizeof(std::uint32_t), &m.triangleSource[k / m.corners],
                    sizeof(std::uint32_t));

    gl_.GenVertexArrays(1, &m.idVao);
    gl_.GenBuffers(1, &m.idVbo);
    state_.bindVao(m.idVao);
    gl_.BindBuffer(GL_ARRAY_BUFFER, m.idVbo);
    gl_.BufferData(GL_ARRAY_BUFFER, size, data.data(), GL_STATIC_DRAW);
    setVertexLayout(m.idVao, m.idVbo, 0, expanded);
    return gl_.GetError() == GL_NO_ERROR;
}

void GlBackend::readBuffer(GLuint buffer, void* data, GLsizeiptr size) {
    if (size <= 0) return;
    // Through GL_COPY_READ_BUFFER: binding GL_ELEMENT_ARRAY_BUFFER would change the bound VAO.
    gl_.BindBuffer(GL_COPY_READ_BUFFER, buffer);
    gl_.GetBufferSubData(GL_COPY_READ_BUFFER, 0, size, data);
    gl_.BindBuffer(GL_COPY_READ_BUFFER, 0);
}

void GlBackend::drawInstances(const DrawParams& params, std::span<const InstanceParams> instances, IndexRange range) {
    GlTarget* target = targets_.find(frameTarget_);
    GlMesh* mesh = meshes_.find(params.mesh);
    assert(target != nullptr && "drawInstances: no beginFrame, or its target was destroyed");
    assert(mesh != nullptr && "drawInstances: no such mesh");
    if (target == nullptr || mesh == nullptr || instances.empty()) return;
    if (mesh->layout.tangent >= 0) {  // its tangents take an instance attribute's location (kTangent)
        Backend::drawInstances(params, instances, range);
        return;
    }
    const std::uint64_t triangles = normalizeRanges({&range, 1}, mesh->triangles, runs_);
    if (triangles == 0) return;
    const IndexRange run = runs_[0];

    activate();
    const bool writeIds = frame_.writeIds;
    GlProgram* p = prepareDraw(params, *target, *mesh, kInstancedBit);
    if (p == nullptr) return;
    // The records: what draw() would put in its uniforms, computed the same way (glm, float).
    instanceData_.resize(instances.size());
    for (std::size_t i = 0; i < instances.size(); ++i) {
        const InstanceParams& in = instances[i];
        InstanceRecord& out = instanceData_[i];
        const glm::mat4 mvp = viewProjection_ * in.model;
        const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(in.model));
        std::memcpy(out.mvp, glm::value_ptr(mvp), sizeof out.mvp);
        std::memcpy(out.normalMatrix, glm::value_ptr(normalMatrix), sizeof out.normalMatrix);
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 4; ++column) out.modelRows[4 * row + column] = in.model[column][row];
        out.firstId = in.firstId;
    }
    if (instanceVbo_ == 0) gl_.GenBuffers(1, &instanceVbo_);
    gl_.BindBuffer(GL_ARRAY_BUFFER, instanceVbo_);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(instanceData_.size() * sizeof(InstanceRecord)), instanceData_.data(),
                   GL_STREAM_DRAW);
    const GLsizei count = GLsizei(instances.size());
    if (writeIds) {
        target->idsDirty = true;
        if (mesh->idVao == 0 && !buildIdPass(*mesh)) {
            assert(false && "drawInstances: could not build the id pass (out of memory?)");
            return;
        }
        attachInstances(mesh->idVao, mesh->idVaoInstanced);
        gl_.DrawArraysInstanced(mesh->mode, GLint(run.firstTriangle * mesh->corners),
                                GLsizei(run.triangleCount * mesh->corners), count);
    } else {
        attachInstances(mesh->vao, mesh->vaoInstanced);
        gl_.DrawElementsInstanced(
            mesh->mode, GLsizei(run.triangleCount * mesh->corners), GL_UNSIGNED_INT,
            reinterpret_cast<const void*>(std::uintptr_t(run.firstTriangle) * mesh->corners * sizeof(std::uint32_t)),
            count);
    }
    state_.countDraw();
    check("drawInstances");
}

void GlBackend::attachInstances(GLuint vao, bool& attached) {
    state_.bindVao(vao);
    if (attached) return;
    gl_.BindBuffer(GL_ARRAY_BUFFER, instanceVbo_);
    constexpr GLsizei stride = sizeof(InstanceRecord);
    const auto at = [](std::size_t bytes) { return reinterpret_cast<const void*>(bytes); };
    for (GLuint column = 0; column < 4; ++column) {
        gl_.EnableVertexAttribArray(kInstanceMvp + column);
        gl_.VertexAttribPointer(kInstanceMvp + column, 4, GL_FLOAT, GL_FALSE, stride,
                                at(offsetof(InstanceRecord, mvp) + 16 * column));
        gl_.VertexAttribDivisor(kInstanceMvp + column, 1);
    }
    for (GLuint column = 0; column < 3; ++column) {
        gl_.EnableVertexAttribArray(kInstanceNormalMatrix + column);
        gl_.VertexAttribPointer(kInstanceNormalMatrix + column, 3, GL_FLOAT, GL_FALSE, stride,
                                at(offsetof(InstanceRecord, normalMatrix) + 12 * column));
        gl_.VertexAttribDivisor(kInstanceNormalMatrix + column, 1);
    }
    for (GLuint row = 0; row < 3; ++row) {
        gl_.EnableVertexAttribArray(kInstanceModelRows + row);
        gl_.VertexAttribPointer(kInstanceModelRows + row, 4, GL_FLOAT, GL_FALSE, stride,
                                at(offsetof(InstanceRecord, modelRows) + 16 * row));
        gl_.VertexAttribDivisor(kInstanceModelRows + row, 1);
    }
    gl_.EnableVertexAttribArray(kInstanceFirstId);
    gl_.VertexAttribIPointer(kInstanceFirstId, 1, GL_UNSIGNED_INT, stride, at(offsetof(InstanceRecord, firstId)));
    gl_.VertexAttribDivisor(kInstanceFirstId, 1);
    attached = true;
}

}  // namespace frugal::gl
