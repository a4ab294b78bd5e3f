#include "app/HsrSupport.h"

namespace frugal {

Flag hsrFlag(hsr::Mode& mode, std::string help) {
    if (help.empty())
        help = R"(zbuffer        the exact render (default)
depthsort      polygons back to front by average depth, no depth test
               (the painter's method; not exact)
adaptive       the same order; only polygons whose x, y and z extents
               overlap another's are depth-tested (equal to zbuffer but
               for rare exact depth ties)
adaptive-convex  adaptive, but the front faces of one convex solid (a
               cube) are not flagged against each other (as exact)
Besides zbuffer, the depth image holds only the depth-tested polygons.
See 'frugal hsr-bench'.)";
    return flag::choice("--hsr", "MODE", "a mode", std::move(help), mode, kHsrs);
}

}  // namespace frugal
