// `frugal-lab shading-bench`'s measurement: what each term of the shading costs on one frame. The
// frame as the settings draw it ("full") and, beside it, the same frame with one term taken away or
// (for anti-aliasing) added: the Lambert model, the environment's specular term, the environment,
// an environment map (its uniform stand-in), the scene's textures, its normal maps, its blending,
// multisampling. Each variant has its own stage (a context of the same backend kind, its own uploads
// and target), and the variants' frames are timed interleaved (the first rotating from round to
// round), each against full's median, with the pixels where its image differs from full's.
#pragma once

#include <functional>
#include <string>

#include <frugal/Result.h>
#include <frugal/Scene.h>
#include <frugal/Settings.h>

#include "lab/ReportText.h"
#include "renderer/Research.h"

namespace frugal {

struct ShadingBenchSettings {
    std::string scene;  // the scene's name in the report
    Settings render;    // the full frame's settings (backend: the one kind the variants open)
    int repeat = 20;    // timed frames per variant
    int warmup = 3;     // untimed frames per variant first
};

// json: {"command","scene","size","backend","renderer","runs","rows":[...],"skipped":[...]}; csv: one row
// per variant; text: one line per variant, as the command prints it.
using ShadingBenchResult = BenchTexts;

// Times `setup`'s frame of `scene` (its parameters before applyShading) as `settings` draw it and
// in every variant that applies to the scene; a variant that does not ("no blending" where nothing
// blends) is listed in "skipped" with why. Errors: the stage's, the upload's.
Result<ShadingBenchResult> measureShadingTerms(const Scene& scene, const FrameSetup& setup,
                                               const ShadingBenchSettings& settings,
                                               const std::function<void(const std::string&)>& progress);

// The gnuplot script that draws the CSV at `csvPath` into `svgPath`: each variant's frame time
// over full's.
std::string shadingBenchGnuplot(const std::string& csvPath, const std::string& svgPath, const std::string& scene);

}  // namespace frugal
