#include "lab/PaperFigures.h"

namespace frugal {

const std::vector<PaperFigure>& paperFigures() {
    using namespace paper003;
    static const std::vector<PaperFigure> figures{
        {"cull paper", "002", "Table 1, Stanford Bunny, partial views", "800x600, Quadro FX5500",
         "97 fps, 144,046 triangles", "295 fps, 41,156 triangles", 97.0 / 295.0, "frame time"},
        {"cull paper", "002", "Table 3, Stanford Bunny, whole object in view", "800x600, Quadro FX5500",
         "97 fps, 144,046 triangles", "136 fps, 80,804 triangles", 97.0 / 136.0, "frame time"},
        {"hsr adaptive", "003", "Table 1, IPAQ 3660", "28 cubes (168 polygons), 240x320, fixed point",
         "z-buffer 14.20 fps", "adaptive z-buffer 27.83 fps", kZBufferFps / kAdaptiveFps, "frame time"},
        {"hsr depthsort", "003", "Table 1, IPAQ 3660", "28 cubes (168 polygons), 240x320, fixed point",
         "z-buffer 14.20 fps", "depth sort 52.13 fps (with ordering errors)", kZBufferFps / kDepthSortFps,
         "frame time"},
        {"reuse", "000", "model I: 804 polygons, 55.44 % static", "software, Pentium II 266 MHz",
         "z-buffer 316 ms a frame", "reuse 170 ms a frame", 170.0 / 316.0, "frame time"},
        {"reuse", "000", "model II: 1,404 polygons, 98.66 % static", "software, Pentium II 266 MHz",
         "z-buffer 158 ms a frame", "reuse 19 ms a frame", 19.0 / 158.0, "frame time"},
        {"order key", "004", "Table 6, 40 state sets", "simulation: 5 states, 3 of high cost",
         "unsorted 921", "sorted by high-cost-state id 334", 334.0 / 921.0, "state-change cost (simulated units)"},
    };
    return figures;
}

}  // namespace frugal
