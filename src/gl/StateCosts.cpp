#include "gl/StateCosts.h"

#include <algorithm>
#include <chrono>
#include <functional>

namespace frugal {
namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0, double unit) {
    return std::chrono::duration<double>(Clock::now() - t0).count() * unit;
}

double medianOf(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A small triangle at the target's centre (a few pixels at 64×64), normal +z; with vertex colours
// when `colours`.
Mesh smallTriangle(bool colours) {
    Mesh mesh;
    mesh.positions = {{-0.05f, -0.05f, 0.0f}, {0.05f, -0.05f, 0.0f}, {0.0f, 0.05f, 0.0f}};
    mesh.normals.assign(3, glm::vec3(0.0f, 0.0f, 1.0f));
    if (colours) mesh.colors.assign(3, glm::vec4(1.0f));
    mesh.uvs = {{0.0f, 0.0f}, {1.0f, 0.0f}, {0.5f, 1.0f}};
    mesh.indices = {0, 1, 2};
    mesh.triangleSource = {0};
    return mesh;
}

Texture checker(int side, std::uint8_t shade) {
    Texture texture;
    texture.name = "state-costs";
    texture.width = texture.height = side;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const std::uint8_t v = (x + y) % 2 ? shade : std::uint8_t(255);
            texture.rgba.insert(texture.rgba.end(), {v, v, v, 255});
        }
    return texture;
}

// Everything measureStateCosts made on the backend, released on every path out.
struct Resources {
    Backend& backend;
    TargetHandle target = kNoHandle;
    std::vector<MeshHandle> meshes;
    std::vector<TextureHandle> textures;
    ~Resources() {
        for (MeshHandle m : meshes) backend.releaseMesh(m);
        for (TextureHandle t : textures) backend.releaseTexture(t);
        if (target != kNoHandle) backend.destroyTarget(target);
    }
};

}  // namespace

Result<StateCostReport> measureStateCosts(Backend& backend, int rounds, int draws) {
    rounds = std::max(rounds, 1);
    draws = std::max(draws, 1);
    Resources made{backend, backend.createTarget(64, 64), {}, {}};
    if (made.target == kNoHandle) return Error{"state costs: the backend refused a 64x64 target"};
    for (bool colours : {false, false, true}) {
        made.meshes.push_back(backend.uploadMesh(smallTriangle(colours)));
        if (made.meshes.back() == kNoHandle) return Error{"state costs: the backend refused a one-triangle mesh"};
    }
    for (std::uint8_t shade : {std::uint8_t(0), std::uint8_t(128)}) {
        made.textures.push_back(backend.uploadTexture(checker(4, shade)));
        if (made.textures.back() == kNoHandle) return Error{"state costs: the backend refused a 4x4 texture"};
    }
    const MeshHandle plain = made.meshes[0], twin = made.meshes[1], coloured = made.meshes[2];
    const IndexRange all{0, 1};
    FrameParams frame;
    frame.writeIds = false;

    // One round: `draws` draws in one frame, then finish; microseconds per draw.
    const auto round = [&](const std::function<DrawParams(int)>& paramsOf) {
        backend.finish();
        const auto t0 = Clock::now();
        backend.beginFrame(made.target, frame);
        for (int i = 0; i < draws; ++i) backend.draw(paramsOf(i), {&all, 1});
        backend.finish();
        return since(t0, 1e6) / draws;
    };
    DrawParams base;
    base.mesh = plain;
    DrawParams textured = base;
    textured.texture = made.textures[0];
    using Round = std::function<DrawParams(int)>;
    const Round kinds[] = {
        [&](int) { return base; },                                                        // 0 baseline
        [&](int) { return textured; },                                                    // 1 baseline, textured
        [&](int i) { DrawParams p = base; p.mesh = i % 2 ? coloured : plain; return p; },  // 2 program (+ mesh)
        [&](int i) { DrawParams p = base; p.mesh = i % 2 ? twin : plain; return p; },      // 3 mesh
        [&](int i) { DrawParams p = textured; p.texture = made.textures[std::size_t(i % 2)]; return p; },  // 4 texture
        [&](int i) { DrawParams p = base; p.baseColorFactor = i % 2 ? glm::vec4(0.5f) : glm::vec4(1.0f); return p; },  // 5
        [&](int i) { DrawParams p = base; p.doubleSided = i % 2; return p; },              // 6 culling
        [&](int i) { DrawParams p = base; p.depth = i % 2 ? DepthMode::Off : DepthMode::Test; return p; },  // 7 depth
    };
    constexpr int kRounds = 8;
    for (const Round& r : kinds) round(r);  // warm-up: every variant and combination compiled once

    std::vector<double> perRound[kRounds];
    for (int r = 0; r < rounds; ++r)
        for (int k = 0; k < kRounds; ++k) {
            const int which = (k + r) % kRounds;
            perRound[which].push_back(round(kinds[which]));
        }

    StateCostReport report;
    report.backend = backend.name();
    report.renderer = backend.renderer();
    report.rounds = rounds;
    report.draws = draws;
    report.drawUs = medianOf(perRound[0]);
    // Per round: the kind's time per draw less its baseline's (program: less the mesh round's).
    const auto cost = [&](const char* kind, int which, int baseline) {
        std::vector<double> d(perRound[which].size());
        for (std::size_t r = 0; r < d.size(); ++r) d[r] = perRound[which][r] - perRound[baseline][r];
        const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
        report.costs.push_back(StateCost{kind, medianOf(d), *lo, *hi});
    };
    cost("program", 2, 3);
    cost("mesh", 3, 0);
    cost("texture", 4, 1);
    cost("material", 5, 0);
    cost("culling", 6, 0);
    cost("depth", 7, 0);

    // Where the data lives: a new 256×256 texture's upload and first use, against a resident one.
    auto t0 = Clock::now();
    made.textures.push_back(backend.uploadTexture(checker(256, 64)));
    report.textureUploadMs = since(t0, 1e3);
    if (made.textures.back() == kNoHandle) return Error{"state costs: the backend refused a 256x256 texture"};
    DrawParams fresh = textured;
    fresh.texture = made.textures.back();
    const auto timedDraw = [&](const DrawParams& params) {
        backend.finish();
        const auto start = Clock::now();
        backend.beginFrame(made.target, frame);
        backend.draw(params, {&all, 1});
        backend.finish();
        return since(start, 1e3);
    };
    report.textureFirstDrawMs = timedDraw(fresh);
    report.textureResidentDrawMs = timedDraw(fresh);
    // A combination no round drew: vertex colours and a texture, double-sided, without the depth test.
    DrawParams unseen = textured;
    unseen.mesh = coloured;
    unseen.doubleSided = true;
    unseen.depth = DepthMode::Off;
    report.newCombinationMs = timedDraw(unseen);
    report.seenCombinationMs = timedDraw(unseen);
    return report;
}

}  // namespace frugal
