#include "gl/StateCosts.h"

#include <algorithm>
#include <chrono>

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

}  // namespace

struct StateCostProbe::Impl {
    Backend& backend;
    TargetHandle target = kNoHandle;
    std::vector<MeshHandle> meshes;  // plain, its twin, with vertex colours
    std::vector<TextureHandle> textures;
    FrameParams frame;
    IndexRange all{0, 1};

    explicit Impl(Backend& b) : backend(b) { frame.writeIds = false; }
    ~Impl() {
        for (MeshHandle m : meshes) backend.releaseMesh(m);
        for (TextureHandle t : textures) backend.releaseTexture(t);
        if (target != kNoHandle) backend.destroyTarget(target);
    }
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;

    DrawParams base() const {
        DrawParams p;
        p.mesh = meshes[0];
        return p;
    }
    DrawParams textured() const {
        DrawParams p = base();
        p.texture = textures[0];
        return p;
    }
    // Round k's i-th draw: 0 baseline, 1 baseline textured, then each kind alternating two values.
    DrawParams drawOf(int k, int i) const {
        const bool odd = i % 2 != 0;
        DrawParams p = k == 1 || k == 4 ? textured() : base();
        switch (k) {
            case 2: p.mesh = odd ? meshes[2] : meshes[0]; break;  // program (+ mesh)
            case 3: p.mesh = odd ? meshes[1] : meshes[0]; break;  // mesh
            case 4: p.texture = textures[odd ? 1 : 0]; break;
            case 5: p.baseColorFactor = odd ? glm::vec4(0.5f) : glm::vec4(1.0f); break;
            case 6: p.doubleSided = odd; break;
            case 7: p.depth = odd ? DepthMode::Off : DepthMode::Test; break;
            default: break;
        }
        return p;
    }
    // `draws` draws of round k in one frame, then finish: microseconds per draw.
    double time(int k, int draws) {
        backend.finish();
        const auto t0 = Clock::now();
        backend.beginFrame(target, frame);
        for (int i = 0; i < draws; ++i) backend.draw(drawOf(k, i), {&all, 1});
        backend.finish();
        return since(t0, 1e6) / draws;
    }
    // One draw of `params` in a frame of its own, to finish: milliseconds.
    double timedDraw(const DrawParams& params) {
        backend.finish();
        const auto t0 = Clock::now();
        backend.beginFrame(target, frame);
        backend.draw(params, {&all, 1});
        backend.finish();
        return since(t0, 1e3);
    }
};

constexpr int kRoundKinds = 8;  // the two baselines and the six kinds

StateCostProbe::StateCostProbe(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
StateCostProbe::~StateCostProbe() = default;

Result<std::unique_ptr<StateCostProbe>> StateCostProbe::create(Backend& backend) {
    auto impl = std::make_unique<Impl>(backend);
    impl->target = backend.createTarget(64, 64);
    if (impl->target == kNoHandle) return Error{"state costs: the backend refused a 64x64 target"};
    for (bool colours : {false, false, true}) {
        impl->meshes.push_back(backend.uploadMesh(smallTriangle(colours)));
        if (impl->meshes.back() == kNoHandle) return Error{"state costs: the backend refused a one-triangle mesh"};
    }
    for (std::uint8_t shade : {std::uint8_t(0), std::uint8_t(128)}) {
        impl->textures.push_back(backend.uploadTexture(checker(4, shade)));
        if (impl->textures.back() == kNoHandle) return Error{"state costs: the backend refused a 4x4 texture"};
    }
    for (int k = 0; k < kRoundKinds; ++k) impl->time(k, 1);  // every variant and combination compiled once
    return std::unique_ptr<StateCostProbe>(new StateCostProbe(std::move(impl)));
}

StateCostSample StateCostProbe::round(int draws, int phase) {
    draws = std::max(draws, 1);
    double t[kRoundKinds];
    for (int j = 0; j < kRoundKinds; ++j) {
        const int k = (j + phase) % kRoundKinds;
        t[k] = impl_->time(k, draws);
    }
    // Each kind's time per draw less its baseline's (program: less the mesh round's).
    return StateCostSample{t[0], {t[2] - t[3], t[3] - t[0], t[4] - t[1], t[5] - t[0], t[6] - t[0], t[7] - t[0]}};
}

Result<bool> StateCostProbe::measureFirstUse(StateCostReport& report) {
    Impl& p = *impl_;
    const auto t0 = Clock::now();
    p.textures.push_back(p.backend.uploadTexture(checker(256, 64)));
    report.textureUploadMs = since(t0, 1e3);
    if (p.textures.back() == kNoHandle) {
        p.textures.pop_back();
        return Error{"state costs: the backend refused a 256x256 texture"};
    }
    DrawParams fresh = p.textured();
    fresh.texture = p.textures.back();
    report.textureFirstDrawMs = p.timedDraw(fresh);
    report.textureResidentDrawMs = p.timedDraw(fresh);
    // A combination no round drew: vertex colours and a texture, double-sided, without the depth test.
    DrawParams unseen = p.textured();
    unseen.mesh = p.meshes[2];
    unseen.doubleSided = true;
    unseen.depth = DepthMode::Off;
    report.newCombinationMs = p.timedDraw(unseen);
    report.seenCombinationMs = p.timedDraw(unseen);
    return true;
}

void RunningStateCosts::add(const StateCostSample& sample) {
    last_.push_back(sample);
    if (last_.size() > window_) last_.pop_front();
    ++total_;
}

std::vector<double> RunningStateCosts::costsUs() const {
    if (last_.empty()) return {};
    std::vector<double> costs(kStateKinds), v(last_.size());
    const std::size_t trim = v.size() / 4;
    for (std::size_t k = 0; k < kStateKinds; ++k) {
        for (std::size_t r = 0; r < v.size(); ++r) v[r] = last_[r].us[k];
        std::sort(v.begin(), v.end());
        double sum = 0.0;
        for (std::size_t r = trim; r < v.size() - trim; ++r) sum += v[r];
        costs[k] = std::max(sum / double(v.size() - 2 * trim), 0.01);
    }
    return costs;
}

Result<StateCostReport> measureStateCosts(Backend& backend, int rounds, int draws) {
    rounds = std::max(rounds, 1);
    draws = std::max(draws, 1);
    Result<std::unique_ptr<StateCostProbe>> probe = StateCostProbe::create(backend);
    if (!probe) return Error{probe.error().message};
    std::vector<StateCostSample> samples;
    for (int r = 0; r < rounds; ++r) samples.push_back((*probe)->round(draws, r));

    StateCostReport report;
    report.backend = backend.name();
    report.renderer = backend.renderer();
    report.rounds = rounds;
    report.draws = draws;
    std::vector<double> v(samples.size());
    for (std::size_t r = 0; r < samples.size(); ++r) v[r] = samples[r].drawUs;
    report.drawUs = medianOf(v);
    for (std::size_t k = 0; k < kStateKinds; ++k) {
        for (std::size_t r = 0; r < samples.size(); ++r) v[r] = samples[r].us[k];
        const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
        report.costs.push_back(StateCost{kStateKindNames[k], medianOf(v), *lo, *hi});
    }
    Result<bool> firstUse = (*probe)->measureFirstUse(report);
    if (!firstUse) return Error{firstUse.error().message};
    return report;
}

}  // namespace frugal
