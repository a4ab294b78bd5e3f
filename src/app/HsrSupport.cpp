#include "app/HsrSupport.h"

namespace frugal {

bool parseHsrOption(const std::string& flag, ArgCursor& cursor, hsr::Mode& mode) {
    if (flag != "--hsr") return false;
    const std::optional<std::string> value = cursor.value(flag);
    if (!value) return true;
    if (std::optional<hsr::Mode> parsed = fromString(*value, kHsrs))
        mode = *parsed;
    else
        cursor.fail("--hsr " + *value + ": not a mode (zbuffer, depthsort, adaptive or adaptive-convex)");
    return true;
}

const char* hsrOptionHelp() {
    return R"(hidden-surface removal (paper 003; src/hsr/Plan.h):
  --hsr MODE            zbuffer        the exact render (default)
                        depthsort      polygons back to front by average depth, no depth test
                                       (the painter's method; not exact)
                        adaptive       the same order; only polygons whose x, y and z extents
                                       overlap another's are depth-tested (equal to zbuffer but
                                       for rare exact depth ties)
                        adaptive-convex  adaptive, but the front faces of one convex solid (a
                                       cube) are not flagged against each other (as exact)
                        Besides zbuffer, the depth image holds only the depth-tested polygons.
                        See 'frugal hsr-bench'.
)";
}

}  // namespace frugal
