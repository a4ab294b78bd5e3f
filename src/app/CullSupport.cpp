#include "app/CullSupport.h"

#include <ostream>

namespace frugal {

std::vector<Flag> cullFlags(CullOptions& options, bool withMethod) {
    std::vector<Flag> flags;
    if (withMethod)
        flags.push_back(flag::choice(
            "--cull", "METHOD", "a method",
            "none (default), sphere, backface, cones, paper, conservative, occlusion, occlusion-ahead or oracle. "
            "conservative never "
            "drops a triangle that owns a pixel; occlusion is conservative less what is hidden behind what is drawn "
            "anyway and, on llvmpipe's rules, the triangles that own no pixel centre, found on the CPU (the same "
            "pixels; it skips itself where it does not pay; not with --reuse); occlusion-ahead is occlusion's "
            "plan, made on a sequence (--frames) on a thread of its own while the frame before draws; paper reproduces paper 002 and misses "
            "some; oracle draws exactly the visible set found by an id pass (a lower bound, not a shortcut). See "
            "'frugal cull-report' and docs/occlusion.md.",
            options.method, kCulls));
    flags.push_back({"--cull-bins", "TxP", "bins of the spherical barycenter map: T polar by P azimuthal (default 16x32)",
                     [&options](const std::string& text) -> std::string {
                         int t = 0, p = 0;
                         if (!parseIntPair(text, t, p) || t < 1 || t > 1024 || p < 1 || p > 1024)
                             return "is not a bin grid (TxP, each 1 to 1024)";
                         options.bins = MapParams{t, p};
                         return {};
                     }});
    return flags;
}

}  // namespace frugal
