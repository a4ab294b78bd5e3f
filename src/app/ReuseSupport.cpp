#include "app/ReuseSupport.h"

#include "renderer/Backends.h"

namespace frugal {

std::vector<Flag> reuseFlags(ReuseCliOptions& options, RenderOptions& render, bool withSwitch) {
    std::vector<Flag> flags;
    if (withSwitch)
        flags.push_back(flag::on("--reuse", "temporal reuse: with the camera still, copy what static instances render "
                                 "from a static pair (one more target) and redraw only what changed; the images are "
                                 "the same, byte for byte. The JSON gets per-frame state counts.",
                                 options.enabled));
    ReuseSettings& s = options.settings;
    flags.push_back(flag::whole("--reuse-grain", "N", "triangles per extent: N consecutive triangles of a mesh share "
                                "one screen rectangle (default 16; 1 = per triangle as in the paper; 0 = per instance)",
                                s.grain, 0, 1 << 30));
    flags.push_back(flag::whole("--reuse-cell", "PX", "side of the screen-grid cells that copies and clears are made "
                                "of (default 16)", s.cell, 1, 4096));
    flags.push_back(flag::on("--no-fallback", "never fall back to a full render while the camera is still (for "
                             "measuring)", s.fallback, false));
    flags.push_back(flag::on("--exact-static", "keep the static pair exactly the static instances' render (clear and "
                             "redraw around instances that come to rest) instead of paper 000's steps, with which a "
                             "depth tie lost while moving can outlive its frame", s.exactStatic));
    flags.push_back(flag::text("--camera-path", "FILE", "a JSON list of {\"eye\":[x,y,z],\"target\":[x,y,z],"
                               "\"up\":[x,y,z],\"fov\":deg}: entry i is frame A+i of --frames A:B, the last entry "
                               "holds (equal entries = still)", render.cameraPathFile));
    return flags;
}

}  // namespace frugal
