#include "lab/ShadingBench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "lab/ImageCompare.h"
#include "lab/ReportText.h"
#include "renderer/Research.h"

namespace frugal {

namespace {

// One row of the bench: the frame with one change, its own stage, and its times.
struct Variant {
    std::string term;    // "lambert", "no textures", ...
    std::string change;  // what differs from full, for the reader
    Settings settings;
    Scene scene;
    std::optional<Stage> stage;
    FrameParams params;
    std::vector<double> ms;
};

bool anyMaterial(const Scene& scene, const std::function<bool(const Material&)>& test) {
    return std::any_of(scene.materials.begin(), scene.materials.end(), test);
}

// `scene` with `change` made to every material.
Scene withMaterials(const Scene& scene, const std::function<void(Material&)>& change) {
    Scene out = scene;
    for (Material& m : out.materials) change(m);
    return out;
}

}  // namespace

// clang-format off
std::string shadingBenchGnuplot(const std::string& csvPath, const std::string& svgPath, const std::string& scene) {
    using reporttext::gnuplotQuoted;
    return "# frugal-lab shading-bench: each variant's frame time over the full frame's.\n"
           "# Drawn from the CSV; run gnuplot on this file to draw it again.\n"
           "set terminal svg size 760,440 dynamic background rgb 'white'\n"
           "set output " + gnuplotQuoted(svgPath) + "\n"
           "set datafile separator ','\n"
           "set title " + gnuplotQuoted("shading terms: " + scene) + " noenhanced\n"
           "set ylabel 'frame time / full frame (medians)'\n"
           "set yrange [0:*]\n"
           "set style fill solid 0.6 border -1\n"
           "set boxwidth 0.7\n"
           "set xtics rotate by -35 noenhanced\n"
           "set grid ytics\n"
           "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2\n"
           "plot " + gnuplotQuoted(csvPath) + " skip 1 using 0:6:xtic(1) with boxes notitle\n";
}
// clang-format on

Result<ShadingBenchResult> measureShadingTerms(const Scene& scene, const FrameSetup& setup,
                                               const ShadingBenchSettings& settings,
                                               const std::function<void(const std::string&)>& progress) {
    const Settings& base = settings.render;
    std::vector<Variant> variants;
    nlohmann::json skipped = nlohmann::json::array();
    const auto add = [&](std::string term, std::string change, Scene variantScene,
                         const std::function<void(Settings&)>& edit) {
        Variant v{std::move(term), std::move(change), base, std::move(variantScene), std::nullopt, {}, {}};
        edit(v.settings);
        variants.push_back(std::move(v));
    };
    const auto skip = [&skipped](const std::string& term, const std::string& why) {
        skipped.push_back({{"term", term}, {"why", why}});
    };
    const auto same = [](Settings&) {};
    add("full", "the frame as the settings draw it", scene, same);

    const bool full = base.shading == ShadingModel::Full;
    if (full)
        add("lambert", "--shading lambert: the diffuse term alone", scene,
            [](Settings& s) { s.shading = ShadingModel::Lambert; });
    else
        skip("lambert", "the frame is already shaded with the Lambert model");
    const bool environment = base.environment > 0.0f || !base.environmentMap.empty();
    if (full && environment && base.environmentSpecular)
        add("no environment specular", "--no-environment-specular", scene,
            [](Settings& s) { s.environmentSpecular = false; });
    else
        skip("no environment specular", "no environment specular term in the frame");
    if (environment)
        add("no environment", "--environment 0: no image-based light", scene, [](Settings& s) {
            s.environmentMap.clear();
            s.environment = 0.0f;
        });
    else
        skip("no environment", "the frame has no environment");
    if (!base.environmentMap.empty())
        add("uniform environment", "the map's stand-in: --environment 0.3 instead of --environment-map", scene,
            [](Settings& s) { s.environmentMap.clear(); });
    else
        skip("uniform environment", "no --environment-map");
    if (anyMaterial(scene, [](const Material& m) { return m.hasTextures(); }))
        add("no textures", "every texture and map of every material left out",
            withMaterials(scene,
                          [](Material& m) {
                              for (const MaterialMap& map : kMaterialMaps) m.*map.texture = -1;
                          }),
            same);
    else
        skip("no textures", "no material samples a texture");
    if (anyMaterial(scene, [](const Material& m) { return m.normalTexture >= 0 || m.clearcoatNormalTexture >= 0; }))
        add("no normal maps", "the normal maps (and the clear coats') left out",
            withMaterials(scene, [](Material& m) { m.normalTexture = m.clearcoatNormalTexture = -1; }), same);
    else
        skip("no normal maps", "no material has a normal map");
    if (anyMaterial(scene, [](const Material& m) { return m.alphaMode == AlphaMode::Blend; }))
        add("no blending", "BLEND materials drawn opaque (in order, with depth writes)",
            withMaterials(scene,
                          [](Material& m) {
                              if (m.alphaMode == AlphaMode::Blend) m.alphaMode = AlphaMode::Opaque;
                          }),
            same);
    else
        skip("no blending", "no material blends");
    if (base.samples == 1)
        add("samples 4", "--samples 4: multisampled, resolved (the one term added)", scene,
            [](Settings& s) { s.samples = 4; });
    else
        add("samples 1", "--samples 1: one sample a pixel", scene, [](Settings& s) { s.samples = 1; });

    // Each variant's stage; one that cannot be made (4 samples where the backend has fewer, a
    // setting the stage refuses) is skipped with the stage's reason.
    std::string backendName, rendererName;
    for (auto it = variants.begin(); it != variants.end();) {
        Result<Stage> stage = Stage::open(it->settings);
        if (!stage) {
            if (it == variants.begin()) return stage.error();
            skip(it->term, stage.error().message);
            it = variants.erase(it);
            continue;
        }
        it->stage.emplace(std::move(*stage));
        if (Result<bool> uploaded = it->stage->upload(it->scene); !uploaded) return uploaded.error();
        it->params = setup.params;
        applyShading(it->settings, it->params);
        if (it == variants.begin()) {
            backendName = it->stage->backend().name();
            rendererName = it->stage->backend().renderer();
        }
        progress("shading-bench: " + it->term + " ready");
        ++it;
    }

    using Clock = std::chrono::steady_clock;
    const auto frame = [&](Variant& v) {
        Backend& backend = v.stage->backend();
        backend.finish();  // also makes its context current, untimed
        const auto t0 = Clock::now();
        v.stage->renderer().renderFrame(v.stage->target(), base.width, base.height, v.params, setup.world,
                                        base.background);
        backend.finish();
        return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    };
    for (int w = 0; w < settings.warmup; ++w)
        for (Variant& v : variants) frame(v);
    const std::size_t n = variants.size();
    for (int round = 0; round < settings.repeat; ++round)
        for (std::size_t k = 0; k < n; ++k) {
            Variant& v = variants[(k + std::size_t(round)) % n];
            v.ms.push_back(frame(v));
        }

    // Images, untimed: each variant against full's.
    frame(variants[0]);
    const Buffers fullImage = variants[0].stage->backend().readBack(variants[0].stage->target());
    const double fullMedian = median(variants[0].ms);
    nlohmann::json rows = nlohmann::json::array();
    std::ostringstream csv, text;
    csv << "term,median_ms,min_ms,max_ms,pixels_differing,over_full\n";
    for (Variant& v : variants) {
        frame(v);
        const Buffers image = v.stage->backend().readBack(v.stage->target());
        const std::size_t differing = differingColorPixels(image, fullImage);
        const double med = median(v.ms);
        const auto [lo, hi] = std::minmax_element(v.ms.begin(), v.ms.end());
        const double over = med / fullMedian;
        rows.push_back({{"term", v.term},
                        {"change", v.change},
                        {"median_ms", med},
                        {"min_ms", *lo},
                        {"max_ms", *hi},
                        {"pixels_differing", differing},
                        {"over_full", over}});
        csv << reporttext::csvField(v.term) << "," << reporttext::csvNumber(med) << "," << reporttext::csvNumber(*lo)
            << "," << reporttext::csvNumber(*hi) << "," << differing << "," << reporttext::csvNumber(over) << "\n";
        char line[200];
        std::snprintf(line, sizeof line, "%-24s %8.3f ms (%.3f-%.3f)  %5.2fx full  %8zu px differ\n", v.term.c_str(),
                      med, *lo, *hi, over, differing);
        text << line;
    }
    const nlohmann::json report = {{"command", "shading-bench"},
                                   {"scene", settings.scene},
                                   {"size", {base.width, base.height}},
                                   {"backend", backendName},
                                   {"renderer", rendererName},
                                   {"runs", settings.repeat},
                                   {"rows", rows},
                                   {"skipped", skipped}};
    return ShadingBenchResult{report.dump(2) + "\n", csv.str(), text.str()};
}

}  // namespace frugal
