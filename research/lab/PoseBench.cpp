#include "lab/PoseBench.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "lab/ReportText.h"

namespace frugal {

Scene poseBenchTube(int rings, int segments, int joints, float angle) {
    Scene scene;
    scene.source = "pose-bench tube (" + std::to_string(2 * rings * segments) + " triangles, " +
                   std::to_string(joints) + " joints)";
    constexpr float kHeight = 8.0f;
    Mesh tube;
    tube.name = "tube";
    Mesh::Influences influences;
    for (int i = 0; i <= rings; ++i) {
        const float h = kHeight * float(i) / float(rings);
        const float along = h / kHeight * float(joints - 1);
        const int j0 = std::min(int(along), joints - 2);
        const float t = along - float(j0);
        for (int j = 0; j < segments; ++j) {
            const float a = 6.2831853f * float(j) / float(segments);
            const glm::vec3 n(std::cos(a), 0.0f, std::sin(a));
            tube.positions.push_back({0.5f * n.x, h, 0.5f * n.z});
            tube.normals.push_back(n);
            influences.joints.push_back({std::uint32_t(j0), std::uint32_t(j0 + 1), 0u, 0u});
            influences.weights.push_back({1.0f - t, t, 0.0f, 0.0f});
        }
    }
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const auto a = std::uint32_t(i * segments + j), b = std::uint32_t(i * segments + (j + 1) % segments);
            const auto c = a + std::uint32_t(segments), d = b + std::uint32_t(segments);
            tube.indices.insert(tube.indices.end(), {a, c, b, b, c, d});
        }
    tube.influences = {std::move(influences)};
    Material material;
    material.metallicFactor = 0.0f;
    material.roughnessFactor = 0.5f;
    scene.materials.push_back(material);
    tube.material = 0;
    const Result<int> mesh = scene.addMesh(std::move(tube));
    const Result<int> node = mesh ? scene.addInstance(*mesh, glm::mat4(1.0f), "tube") : Result<int>(mesh.error());
    if (!node) return scene;
    Skin skin;
    AnimChannel turn;
    turn.path = AnimPath::Rotation;
    turn.times = {0.0f, 1.0f, 2.0f};
    const glm::quat q = glm::angleAxis(angle, glm::vec3(0.0f, 0.0f, 1.0f));
    turn.values = {{0, 0, 0, 1}, {q.x, q.y, q.z, q.w}, {0, 0, 0, 1}};
    Animation animation{"turn", {}};
    for (int j = 0; j < joints; ++j) {
        Node joint;
        joint.name = "joint " + std::to_string(j);
        joint.translation = {0.0f, j == 0 ? 0.0f : kHeight / float(joints - 1), 0.0f};
        const int index = int(scene.nodes.size());
        if (j == 0)
            scene.roots.push_back(index);
        else {
            joint.parent = index - 1;
            scene.nodes[std::size_t(index - 1)].children.push_back(index);
        }
        scene.nodes.push_back(joint);
        skin.joints.push_back(index);
        skin.inverseBindMatrices.push_back(
            glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, -kHeight * float(j) / float(joints - 1), 0.0f)));
        turn.node = index;
        animation.channels.push_back(turn);
    }
    scene.skins.push_back(std::move(skin));
    scene.nodes[std::size_t(*node)].skin = 0;
    scene.animations.push_back(std::move(animation));
    scene.buildInstances();
    return scene;
}

namespace {

struct Variant {
    std::string name;
    Scene scene;
    std::optional<Stage> stage;
    std::vector<double> ms;
};

// `scene` without its skins and morph targets: the same meshes in their rest pose.
Scene restPose(const Scene& scene) {
    Scene out = scene;
    for (Node& node : out.nodes) node.skin = -1;
    for (Mesh& mesh : out.meshes) {
        mesh.targets.clear();
        mesh.weights.clear();
        mesh.influences.clear();
    }
    for (Animation& animation : out.animations)
        std::erase_if(animation.channels, [](const AnimChannel& c) { return c.path == AnimPath::Weights; });
    out.buildInstances();
    return out;
}

}  // namespace

// clang-format off
std::string poseBenchGnuplot(const std::string& csvPath, const std::string& svgPath, const std::string& scene) {
    using reporttext::gnuplotQuoted;
    return "# frugal-lab pose-bench: the deforming scene's frame time beside its rest pose's.\n"
           "# Drawn from the CSV; run gnuplot on this file to draw it again.\n"
           "set terminal svg size 560,400 dynamic background rgb 'white'\n"
           "set output " + gnuplotQuoted(svgPath) + "\n"
           "set datafile separator ','\n"
           "set title " + gnuplotQuoted("poses: " + scene) + " noenhanced\n"
           "set ylabel 'frame time (ms, median; bars: min to max)'\n"
           "set yrange [0:*]\n"
           "set style fill solid 0.6 border -1\n"
           "set boxwidth 0.6\n"
           "set grid ytics\n"
           "plot " + gnuplotQuoted(csvPath) + " skip 1 using 0:2:xtic(1) with boxes notitle, \\\n"
           "     '' skip 1 using 0:2:3:4 with yerrorbars notitle lc rgb 'black'\n";
}
// clang-format on

Result<BenchTexts> measurePoses(const Scene& scene, const FrameSetup& setup, const PoseBenchSettings& settings,
                                const std::function<void(const std::string&)>& progress) {
    std::size_t deforming = 0, vertices = 0;
    for (const Instance& instance : scene.instances)
        if (scene.deforms(instance)) {
            ++deforming;
            vertices += scene.meshes[std::size_t(instance.mesh)].positions.size();
        }
    if (deforming == 0)
        return Error{"pose-bench: '" + scene.source + "' has no mesh that deforms (no skin, no morph targets)",
                     ErrorKind::BadInput};
    const Settings& base = settings.render;
    std::vector<Variant> variants;
    variants.push_back({"deforming", scene, std::nullopt, {}});
    variants.push_back({"rest pose", restPose(scene), std::nullopt, {}});
    std::string backendName, rendererName;
    for (Variant& v : variants) {
        Result<Stage> stage = Stage::open(base);
        if (!stage) return stage.error();
        v.stage.emplace(std::move(*stage));
        if (Result<bool> uploaded = v.stage->upload(v.scene); !uploaded) return uploaded.error();
        backendName = v.stage->backend().name();
        rendererName = v.stage->backend().renderer();
        progress("pose-bench: " + v.name + " ready");
    }

    // Frame k at time k·step: a pose differs from the one before it at every frame (the scene's
    // animation, or 2 s, spread over the frames and wrapped).
    const double duration = scene.duration() > 0.0 ? scene.duration() : 2.0;
    const int frames = settings.warmup + settings.repeat;
    const double step = duration / double(frames + 1);
    using Clock = std::chrono::steady_clock;
    const auto frame = [&](Variant& v, int k) {
        const double time = step * double(k + 1);
        FrameParams params = setup.params;
        params.time = time;
        const std::vector<glm::mat4> world = v.scene.worldTransforms(time);
        Backend& backend = v.stage->backend();
        backend.finish();  // also makes its context current, untimed
        const auto t0 = Clock::now();
        v.stage->renderer().renderFrame(v.stage->target(), base.width, base.height, params, world, base.background);
        backend.finish();
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    };
    for (int k = 0; k < frames; ++k)
        for (std::size_t i = 0; i < variants.size(); ++i) {
            Variant& v = variants[(i + std::size_t(k)) % variants.size()];  // which goes first alternates
            const double ms = frame(v, k);
            if (k >= settings.warmup) v.ms.push_back(ms);
        }

    const double restMedian = median(variants[1].ms);
    nlohmann::json rows = nlohmann::json::array();
    std::ostringstream csv, text;
    csv << "variant,median_ms,min_ms,max_ms,over_rest\n";
    for (const Variant& v : variants) {
        const double med = median(v.ms);
        const auto [lo, hi] = std::minmax_element(v.ms.begin(), v.ms.end());
        const double over = med / restMedian;
        rows.push_back({{"variant", v.name}, {"median_ms", med}, {"min_ms", *lo}, {"max_ms", *hi}, {"over_rest", over}});
        csv << reporttext::csvField(v.name) << "," << reporttext::csvNumber(med) << "," << reporttext::csvNumber(*lo)
            << "," << reporttext::csvNumber(*hi) << "," << reporttext::csvNumber(over) << "\n";
        char line[200];
        std::snprintf(line, sizeof line, "%-10s %8.3f ms (%.3f-%.3f)  %5.3fx the rest pose\n", v.name.c_str(), med,
                      *lo, *hi, over);
        text << line;
    }
    const nlohmann::json report = {{"command", "pose-bench"},
                                   {"scene", settings.scene},
                                   {"size", {base.width, base.height}},
                                   {"backend", backendName},
                                   {"renderer", rendererName},
                                   {"runs", settings.repeat},
                                   {"deforming_instances", deforming},
                                   {"vertices_posed", vertices},
                                   {"rows", rows}};
    return BenchTexts{report.dump(2) + "\n", csv.str(), text.str()};
}

}  // namespace frugal
