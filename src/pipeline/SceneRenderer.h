// Draws a Scene through a Backend: uploads its meshes and textures once, then executes draw lists.
#pragma once

#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <frugal/Result.h>

#include "base/ThreadPool.h"
#include "pipeline/Backend.h"
#include "pipeline/Plan.h"

namespace frugal {

class SceneRenderer {
public:
    // Uploads every mesh and texture of `scene`; both must outlive the renderer. A mesh or texture
    // the backend refuses is an error, never a part of the scene left out of every frame:
    // "mesh 2 'name' (N vertices, M triangles): <backend> refused it ..." or the same for a texture.
    // `mipmaps` false: every texture is uploaded without its mipmaps (MipFilter::None), so it is
    // sampled from its base level.
    static Result<SceneRenderer> create(Backend& backend, const Scene& scene, bool mipmaps = true);

    // Releases what it uploaded (the backend must still be alive).
    ~SceneRenderer();
    SceneRenderer(SceneRenderer&& other) noexcept;
    SceneRenderer& operator=(SceneRenderer&& other) noexcept;
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    // Poses the deforming instances (Scene::deforms: morph targets, skins) at scene time `time`:
    // each is drawn from a mesh of its own, posed on the CPU (poseVertices) by its node's weights
    // and its skin's joint matrices, its positions, normals and tangents updated in place when they
    // change (Backend::updateVertices; a mesh whose tangents are generated for a normal map is
    // uploaded again, tangents and all), so both backends draw the same vertices. renderFrame and
    // execute pose at
    // their frame's time; nothing to do in a scene without morph targets. An upload the backend
    // refuses throws std::bad_alloc (a frame cannot be drawn without it).
    void pose(double time);

    // Draws `list` with the node transforms `world` into the current frame (Backend::beginFrame
    // must have been called), seen through `view`. Materials follow the instance's mesh. Commands
    // of blended materials (AlphaMode::Blend) are drawn after all the others, far to near by the
    // view depth of their mesh's centroid (blendOrder); the rest in list order.
    void draw(const DrawList& list, const std::vector<glm::mat4>& world, const glm::mat4& view);

    // The usual full frame: clear the whole target to `background`, begin, draw everything.
    void renderFrame(TargetHandle target, int width, int height, const FrameParams& frame,
                     const std::vector<glm::mat4>& world, const glm::vec4& background);
    // The same with a plan of its own (culling): clear, begin, draw `list`.
    void renderFrame(TargetHandle target, int width, int height, const FrameParams& frame,
                     const std::vector<glm::mat4>& world, const glm::vec4& background, const DrawList& list);

    // Executes a frame plan (pipeline/Plan.h): Render is `target`, Static is `staticTarget` (both
    // width × height; kNoHandle for a plan that never names the static pair).
    void execute(const FramePlan& plan, TargetHandle target, TargetHandle staticTarget, const FrameParams& frame,
                 const std::vector<glm::mat4>& world, const glm::vec4& background);

    // true: every draw culls back faces, whatever its material says (the fair timing baseline of
    // culling reports: the full draw with GL face culling on). false (default): as materials say.
    void setCullAllBackFaces(bool on) { cullAllBackFaces_ = on; }

    // true (default): consecutive draws of one mesh with one range and depth mode go to the backend
    // as one Backend::drawInstances (the same pixels, one GL draw call). false: one draw each.
    void setBatching(bool on) { batching_ = on; }

    // The full draw list (fullDrawList of the scene), as renderFrame draws it.
    const DrawList& fullList() const { return full_; }

    Backend& backend() { return *backend_; }
    const Scene& scene() const { return *scene_; }

private:
    SceneRenderer(Backend& backend, const Scene& scene);
    void drawSequence(std::span<const DrawCommand* const> sequence, const std::vector<glm::mat4>& world);
    void release();
    // `mesh` as the backend draws it (with generated tangents when its material needs them).
    MeshHandle upload(const Mesh& mesh) const;
    // Whether upload() gives `mesh` generated tangents (a normal map and none of its own).
    bool generatesTangents(const Mesh& mesh) const;

    Backend* backend_;
    const Scene* scene_;
    DrawList full_;
    std::vector<MeshHandle> meshes_;
    // Deforming instances (Scene::deforms): per instance its slot in posed_ (-1: drawn from
    // meshes_), and per slot the uploaded posed mesh and the pose it was made with.
    struct Posed {
        std::vector<float> weights;
        std::vector<glm::mat4> joints;
        PosedVertices vertices;  // the arrays updated, kept from frame to frame
    };
    std::vector<int> posedSlot_;
    std::vector<MeshHandle> posed_;
    std::vector<Posed> posedPose_;
    // Poses a large mesh on two threads (pose(): the vertex ranges of scene/Posing.h), made only
    // when a deforming mesh has kParallelPoseVertices vertices or more and the machine two cores.
    std::unique_ptr<ThreadPool> posePool_;
    std::vector<TextureHandle> textures_;
    bool cullAllBackFaces_ = false;
    bool batching_ = true;
    std::vector<glm::vec3> centroids_;  // per mesh: the mean of its indexed positions (blendOrder)
    std::vector<InstanceParams> instances_;  // draw()'s scratch
    std::vector<const DrawCommand*> sequence_;
    std::vector<std::pair<float, std::uint32_t>> blendKeys_;
};

}  // namespace frugal
