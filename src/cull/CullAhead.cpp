#include "cull/CullAhead.h"

#include <cstring>
#include <utility>

namespace frugal {

namespace {

// Bit for bit: a NaN in one is a different frame, as is -0 for +0 (the plan could differ).
template <typename T>
bool sameBits(const T& a, const T& b) {
    return std::memcmp(&a, &b, sizeof(T)) == 0;
}

bool sameView(const View& a, const View& b) {
    return sameBits(a.view, b.view) && sameBits(a.projection, b.projection) &&
           sameBits(a.givenProjection, b.givenProjection) && sameBits(a.eye, b.eye) &&
           sameBits(a.forward, b.forward) && a.perspective == b.perspective && sameBits(a.yfov, b.yfov) &&
           sameBits(a.ymag, b.ymag) && sameBits(a.aspect, b.aspect) && sameBits(a.fileAspect, b.fileAspect) &&
           sameBits(a.znear, b.znear) && sameBits(a.zfar, b.zfar) && sameBits(a.givenNear, b.givenNear) &&
           sameBits(a.givenFar, b.givenFar) && a.depthRange == b.depthRange && a.depthFormat == b.depthFormat &&
           a.width == b.width && a.height == b.height;
}

bool sameTarget(const OcclusionTarget& a, const OcclusionTarget& b) {
    return a.width == b.width && a.height == b.height && a.exactRules == b.exactRules &&
           sameBits(a.drawNsPerTriangle, b.drawNsPerTriangle) &&
           sameBits(a.drawNsPerDraw, b.drawNsPerDraw) && a.gathering == b.gathering && a.adaptive == b.adaptive &&
           a.simd == b.simd;
}

bool sameWorld(const std::vector<glm::mat4>& a, const std::vector<glm::mat4>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::mat4)) == 0);
}

}  // namespace

OcclusionTarget aheadTarget(OcclusionTarget target) {
    target.threads = 1;
    return target;
}

void CullAhead::start(const SceneCuller& culler, Cull method, const Scene& scene, std::vector<glm::mat4> world,
                      const View& view, const OcclusionTarget& target) {
    settle();
    key_ = Key{method, std::move(world), view, target};
    // The thread reads key_'s copies, which stay put until take() or settle() has waited for it.
    plan_ = std::async(std::launch::async, [&culler, &scene, this] {
        return culler.cull(key_.method, scene, key_.world, key_.view, key_.target);
    });
}

std::optional<DrawList> CullAhead::take(Cull method, const std::vector<glm::mat4>& world, const View& view,
                                        const OcclusionTarget& target) {
    if (!plan_.valid()) return std::nullopt;
    DrawList plan = plan_.get();  // waits; rethrows what the cull threw (std::bad_alloc)
    if (key_.method != method || !sameWorld(key_.world, world) || !sameView(key_.view, view) ||
        !sameTarget(key_.target, target))
        return std::nullopt;
    return plan;
}

void CullAhead::settle() {
    if (plan_.valid()) plan_.wait();
    plan_ = {};
}

}  // namespace frugal
