// One pose of one mesh (poseVertices, frugal/Scene.h) computed by vertex ranges: the constructor
// sizes the output and prepares what every vertex shares (the joints' normal matrices, whether
// normals are renormalised), run() poses the vertices of a range. Ranges are independent, so
// disjoint ones may run on threads of their own; each vertex gets the same floats whatever the split.
#pragma once

#include <cstddef>
#include <vector>

#include <frugal/Scene.h>

namespace frugal {

// `mesh` drawn in `posed` (its arrays moved in): what posedMesh returns, a mesh without targets or
// influences, for an upload.
Mesh withPose(const Mesh& mesh, PosedVertices&& posed);

class Posing {
public:
    Posing(const Mesh& mesh, const std::vector<float>& weights, const std::vector<glm::mat4>& joints,
           PosedVertices& out, bool frames);
    std::size_t vertices() const { return mesh_.positions.size(); }
    // Poses vertices [begin, end).
    void run(std::size_t begin, std::size_t end) const;

private:
    const Mesh& mesh_;
    const std::vector<float>& weights_;
    const std::vector<glm::mat4>& joints_;
    PosedVertices& out_;
    std::vector<glm::mat3> normalMatrices_;  // per joint, when skinning normals
    bool skinning_ = false, renormalise_ = false;
};

}  // namespace frugal
