#include "pipeline/SceneRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <string>
#include <thread>
#include <utility>

#include "base/Format.h"
#include "scene/MeshBuild.h"
#include "scene/Posing.h"

namespace frugal {

namespace {

// From this many vertices a pose is split over two threads: waking a thread costs tens of
// microseconds (base/ThreadPool.h), posing 16,384 skinned vertices about a quarter of a millisecond.
constexpr std::size_t kParallelPoseVertices = 16384;

}  // namespace

SceneRenderer::SceneRenderer(Backend& backend, const Scene& scene)
    : backend_(&backend), scene_(&scene), full_(fullDrawList(scene)) {}

SceneRenderer::~SceneRenderer() { release(); }

SceneRenderer::SceneRenderer(SceneRenderer&& other) noexcept
    : backend_(other.backend_), scene_(other.scene_), full_(std::move(other.full_)),
      meshes_(std::exchange(other.meshes_, {})), posedSlot_(std::move(other.posedSlot_)),
      posed_(std::exchange(other.posed_, {})), posedPose_(std::move(other.posedPose_)),
      posePool_(std::move(other.posePool_)), textures_(std::exchange(other.textures_, {})),
      cullAllBackFaces_(other.cullAllBackFaces_), batching_(other.batching_),
      centroids_(std::move(other.centroids_)) {}

SceneRenderer& SceneRenderer::operator=(SceneRenderer&& other) noexcept {
    if (this != &other) {
        release();
        backend_ = other.backend_;
        scene_ = other.scene_;
        full_ = std::move(other.full_);
        meshes_ = std::exchange(other.meshes_, {});
        posedSlot_ = std::move(other.posedSlot_);
        posed_ = std::exchange(other.posed_, {});
        posedPose_ = std::move(other.posedPose_);
        posePool_ = std::move(other.posePool_);
        textures_ = std::exchange(other.textures_, {});
        cullAllBackFaces_ = other.cullAllBackFaces_;
        batching_ = other.batching_;
        centroids_ = std::move(other.centroids_);
    }
    return *this;
}

void SceneRenderer::release() {
    for (MeshHandle mesh : meshes_) backend_->releaseMesh(mesh);
    for (MeshHandle mesh : posed_)
        if (mesh != kNoHandle) backend_->releaseMesh(mesh);
    for (TextureHandle texture : textures_) backend_->releaseTexture(texture);
    meshes_.clear();
    posed_.clear();
    textures_.clear();
}

bool SceneRenderer::generatesTangents(const Mesh& mesh) const {
    // A normal map (the surface's or its coat's) needs tangents: a mesh of triangles without them is
    // uploaded with generated ones (segments and points without tangents ignore normal maps, as the
    // Khronos renderer draws them).
    return mesh.tangents.empty() && mesh.triangles() && mesh.material >= 0 &&
           std::size_t(mesh.material) < scene_->materials.size() &&
           scene_->materials[std::size_t(mesh.material)].tangentSpace();
}

MeshHandle SceneRenderer::upload(const Mesh& mesh) const {
    if (!generatesTangents(mesh)) return backend_->uploadMesh(mesh);
    Mesh withTangents = mesh;
    generateTangents(withTangents);
    return backend_->uploadMesh(withTangents);
}

void SceneRenderer::pose(double time) {
    if (posed_.empty()) return;
    if (posePool_) posePool_->warm(std::chrono::microseconds(2000));  // it wakes while the joints are computed
    const std::vector<std::vector<float>> weights = scene_->morphWeights(time);
    // Node matrices only for joints to follow (a scene of morph targets alone needs none).
    const std::vector<glm::mat4> world =
        scene_->skins.empty() ? std::vector<glm::mat4>{} : scene_->worldTransforms(time);
    for (std::size_t i = 0; i < posedSlot_.size(); ++i) {
        const int slot = posedSlot_[i];
        if (slot < 0) continue;
        const Instance& instance = scene_->instances[i];
        const std::vector<float>& w = weights[std::size_t(instance.node)];
        std::vector<glm::mat4> joints = scene_->jointMatrices(instance, world);
        Posed& posed = posedPose_[std::size_t(slot)];
        MeshHandle& handle = posed_[std::size_t(slot)];
        if (handle != kNoHandle && posed.weights == w && posed.joints == joints) continue;
        const Mesh& mesh = scene_->meshes[std::size_t(instance.mesh)];
        const Posing posing(mesh, w, joints, posed.vertices, /*frames=*/true);
        const std::size_t n = posing.vertices();
        if (posePool_ && n >= kParallelPoseVertices) {
            // In pieces, so that the worker, woken at the start of pose(), takes its share as soon
            // as it is up.
            constexpr std::size_t kPieces = 32;
            posePool_->run(kPieces,
                           [&](std::size_t piece, int) { posing.run(n * piece / kPieces, n * (piece + 1) / kPieces); });
        } else {
            posing.run(0, n);
        }
        // In place, unless its tangents are made from its posed shape (upload): then all again.
        if (handle == kNoHandle || generatesTangents(mesh) ||
            !backend_->updateVertices(handle, posed.vertices.positions, posed.vertices.normals,
                                      posed.vertices.tangents)) {
            const MeshHandle uploaded = upload(withPose(mesh, PosedVertices(posed.vertices)));
            if (uploaded == kNoHandle) throw std::bad_alloc();
            if (handle != kNoHandle) backend_->releaseMesh(handle);
            handle = uploaded;
        }
        posed.weights = w;
        posed.joints = std::move(joints);
    }
    if (posePool_) posePool_->rest();
}

Result<SceneRenderer> SceneRenderer::create(Backend& backend, const Scene& scene, bool mipmaps) {
    SceneRenderer renderer(backend, scene);
    renderer.meshes_.reserve(scene.meshes.size());
    renderer.posedSlot_.assign(scene.instances.size(), -1);
    bool large = false;
    for (std::size_t i = 0; i < scene.instances.size(); ++i)
        if (scene.deforms(scene.instances[i])) {
            renderer.posedSlot_[i] = int(renderer.posed_.size());
            renderer.posed_.push_back(kNoHandle);
            renderer.posedPose_.emplace_back();
            large =
                large || scene.meshes[std::size_t(scene.instances[i].mesh)].positions.size() >= kParallelPoseVertices;
        }
    if (large && std::thread::hardware_concurrency() >= 2) renderer.posePool_ = std::make_unique<ThreadPool>(2);
    for (std::size_t i = 0; i < scene.meshes.size(); ++i) {
        const Mesh& mesh = scene.meshes[i];
        const MeshHandle handle = renderer.upload(mesh);
        if (handle == kNoHandle)
            return Error{"mesh " + std::to_string(i) + quotedName(mesh.name) + " (" + std::to_string(mesh.positions.size()) +
                         " vertices, " + std::to_string(mesh.triangleCount()) + " triangles): " + backend.name() +
                         (isUploadable(mesh) ? " could not store it (out of memory)"
                                             : " refused it: its arrays break the upload contract (pipeline/Backend.h)")};
        renderer.meshes_.push_back(handle);
        // The blend order's centroid: the mean of the positions the indices name (the Khronos
        // renderer's, which counts a vertex once per use).
        glm::dvec3 sum(0.0);
        for (const std::uint32_t index : mesh.indices) sum += glm::dvec3(mesh.positions[index]);
        const double uses = double(mesh.indices.size());
        renderer.centroids_.push_back(mesh.indices.empty() ? glm::vec3(0.0f) : glm::vec3(sum / uses));
    }
    renderer.textures_.reserve(scene.textures.size());
    for (std::size_t i = 0; i < scene.textures.size(); ++i) {
        const Texture& texture = scene.textures[i];
        TextureHandle handle = kNoHandle;
        if (mipmaps || texture.mipmaps == MipFilter::None) {
            handle = backend.uploadTexture(texture);
        } else {
            Texture base = texture;
            base.mipmaps = MipFilter::None;
            handle = backend.uploadTexture(base);
        }
        if (handle == kNoHandle)
            return Error{"texture " + std::to_string(i) + quotedName(texture.name) + " (" + std::to_string(texture.width) +
                         "x" + std::to_string(texture.height) + "): " + backend.name() +
                         " refused it (its limit is " + std::to_string(backend.maxTextureSize()) +
                         " pixels a side; or out of memory)"};
        renderer.textures_.push_back(handle);
    }
    try {
        renderer.pose(0.0);  // so that a draw before the first frame finds every posed mesh
    } catch (const std::bad_alloc&) {
        return Error{"a deforming mesh posed at time 0: " + backend.name() + " could not store it (out of memory)"};
    }
    return renderer;
}

void SceneRenderer::draw(const DrawList& list, const std::vector<glm::mat4>& world, const glm::mat4& view) {
    sequence_.clear();
    blendKeys_.clear();
    const bool blending = anyBlended(*scene_);
    for (std::size_t i = 0; i < list.size(); ++i) {
        if (blending && blendedInstance(*scene_, list[i].instance)) {
            // The view depth of the centroid: eye-space z, more negative farther (the Khronos
            // renderer's sortPrimitivesByDepth, a stable sort on it, far first).
            const Instance& instance = scene_->instances[list[i].instance];
            const glm::vec4 at = (view * world[instance.node]) * glm::vec4(centroids_[instance.mesh], 1.0f);
            blendKeys_.emplace_back(at.z, std::uint32_t(i));
        } else {
            sequence_.push_back(&list[i]);
        }
    }
    // NaN depths (a degenerate pose) sort first, and keep their order.
    std::stable_sort(blendKeys_.begin(), blendKeys_.end(), [](const auto& a, const auto& b) {
        return std::isnan(a.first) ? !std::isnan(b.first) : a.first < b.first;
    });
    for (const auto& key : blendKeys_) sequence_.push_back(&list[key.second]);
    drawSequence(sequence_, world);
}

void SceneRenderer::drawSequence(std::span<const DrawCommand* const> list, const std::vector<glm::mat4>& world) {
    static const Material kDefault{};
    const auto paramsOf = [&](const DrawCommand& command) {
        const Instance& instance = scene_->instances[command.instance];
        const Mesh& mesh = scene_->meshes[instance.mesh];
        const Material& material = mesh.material >= 0 ? scene_->materials[mesh.material] : kDefault;
        DrawParams params;
        const int slot = posedSlot_[std::size_t(command.instance)];
        params.mesh = slot >= 0 ? posed_[std::size_t(slot)] : meshes_[instance.mesh];
        params.model = world[instance.node];
        params.baseColorFactor = material.baseColorFactor;
        params.metallic = material.metallicFactor;
        params.roughness = material.roughnessFactor;
        params.unlit = material.unlit;
        params.emissive = material.emissiveFactor;
        params.uvTransform = material.baseColorTransform;
        const auto handle = [this](int texture) { return texture >= 0 ? textures_[texture] : kNoHandle; };
        params.texture = handle(material.baseColorTexture);
        params.metallicRoughnessTexture = handle(material.metallicRoughnessTexture);
        params.occlusionTexture = handle(material.occlusionTexture);
        params.occlusionStrength = material.occlusionStrength;
        params.emissiveTexture = handle(material.emissiveTexture);
        params.normalTexture = handle(material.normalTexture);
        params.normalScale = material.normalScale;
        params.doubleSided = material.doubleSided && !cullAllBackFaces_;
        params.alphaMode = material.alphaMode;
        params.alphaCutoff = material.alphaCutoff;
        params.specularGlossiness = material.specularGlossiness;
        params.specular = material.specularFactor;
        params.glossiness = material.glossinessFactor;
        params.specularGlossinessTexture = handle(material.specularGlossinessTexture);
        if (material.clearcoat()) {
            params.clearcoat = material.clearcoatFactor;
            params.clearcoatRoughness = material.clearcoatRoughnessFactor;
            params.clearcoatTexture = handle(material.clearcoatTexture);
            params.clearcoatRoughnessTexture = handle(material.clearcoatRoughnessTexture);
            params.clearcoatNormalTexture = handle(material.clearcoatNormalTexture);
            params.clearcoatNormalScale = material.clearcoatNormalScale;
        }
        params.firstId = instance.firstId;
        params.depth = command.depth;
        return params;
    };
    // A batch: consecutive commands of one mesh (so one material), one depth mode and one range,
    // the same in each. Drawing them as instances keeps the order, so the pixels are the same.
    const auto batchable = [&](const DrawCommand& a, const DrawCommand& b) {
        return a.ranges.size() == 1 && b.ranges.size() == 1 && a.ranges[0] == b.ranges[0] && a.depth == b.depth &&
               scene_->instances[a.instance].mesh == scene_->instances[b.instance].mesh &&
               posedSlot_[std::size_t(a.instance)] < 0;
    };
    for (std::size_t i = 0; i < list.size();) {
        const DrawCommand& command = *list[i];
        if (command.ranges.empty()) {
            ++i;
            continue;
        }
        std::size_t end = i + 1;
        if (batching_)
            while (end < list.size() && batchable(command, *list[end])) ++end;
        if (end - i < 2) {
            backend_->draw(paramsOf(command), command.ranges);
            i = end;
            continue;
        }
        instances_.clear();
        for (std::size_t k = i; k < end; ++k) {
            const Instance& instance = scene_->instances[list[k]->instance];
            instances_.push_back(InstanceParams{world[instance.node], instance.firstId});
        }
        backend_->drawInstances(paramsOf(command), instances_, command.ranges[0]);
        i = end;
    }
}

void SceneRenderer::renderFrame(TargetHandle target, int width, int height, const FrameParams& frame,
                                const std::vector<glm::mat4>& world, const glm::vec4& background) {
    renderFrame(target, width, height, frame, world, background, full_);
}

void SceneRenderer::renderFrame(TargetHandle target, int width, int height, const FrameParams& frame,
                                const std::vector<glm::mat4>& world, const glm::vec4& background, const DrawList& list) {
    pose(frame.time);
    backend_->clear(target, Rect{0, 0, width, height}, background, farDepth(frame.depthFormat));
    backend_->beginFrame(target, frame);
    draw(list, world, frame.view);
}

void SceneRenderer::execute(const FramePlan& plan, TargetHandle target, TargetHandle staticTarget,
                            const FrameParams& frame, const std::vector<glm::mat4>& world, const glm::vec4& background) {
    pose(frame.time);
    const auto handle = [&](PlanTarget which) { return which == PlanTarget::Render ? target : staticTarget; };
    TargetHandle drawing = kNoHandle;  // the target of the frame begun last
    for (const PlanStep& step : plan) {
        switch (step.op) {
        case PlanStep::Op::Clear:
            for (const Rect& rect : step.rects)
                backend_->clear(handle(step.to), rect, background, farDepth(frame.depthFormat));
            break;
        case PlanStep::Op::Copy:
            // Ids only when the frame writes them: otherwise both targets hold the zeros of their last
            // whole clear (a frame that changes writeIds is never a reuse frame).
            for (const Rect& rect : step.rects)
                backend_->copy(handle(step.from), handle(step.to), rect, true, true, frame.writeIds);
            break;
        case PlanStep::Op::Draw:
            if (drawing != handle(step.to)) backend_->beginFrame(handle(step.to), frame);
            drawing = handle(step.to);
            draw(step.list ? *step.list : step.draws, world, frame.view);
            break;
        }
    }
}

}  // namespace frugal
