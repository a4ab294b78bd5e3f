// frugal-lab: the research commands (the benchmarks and the papers' reproductions) beside frugal's.
#include "commands/LabCommands.h"

#include "app/Commands.h"

namespace frugal {

const Program& labProgram() {
    static const Program program = [] {
        Program p{"frugal-lab",
                  "frugal-lab — frugal's research harnesses: benchmarks, the seed papers' figures, and frugal's commands",
                  {
                      {"bench", "render [SCENE] [options]", "frame time per backend, as JSON", runBench},
                      {"reuse-bench", "[SCENE] --frames A:B [opts]", "what temporal reuse saves, frame by frame",
                       runReuseBench},
                      {"order-bench", "[SCENE] [options]", "a frame in every draw order: time, state changes, ties",
                       runOrderBench},
                      {"hsr-bench", "[SCENE] [options]", "depth sort and the adaptive z-buffer against the z-buffer",
                       runHsrBench},
                      {"shading-bench", "[SCENE] [options]", "what each shading term costs on a frame",
                       runShadingBench},
                      {"pose-bench", "[SCENE] [options]", "what skins and morph targets cost a frame",
                       runPoseBench},
                      {"span-bench", "[options]", "paper 001's shading engine model: Fig. 11, error tables",
                       runSpanBench},
                      {"write-bench", "[--scene SCENE ...] [opts]",
                       "PNG levels and filters: time against size; sequence wall time", runWriteBench},
                      {"state-sim", "[options]", "paper 004's draw orders on random state sets: Tables 6, 7",
                       runStateSim},
                      {"compress", "IN.gltf OUT.gltf (--draco | --meshopt)",
                       "a compressed copy of a glTF file, to test and time the decoders", runCompress},
                      {"soak", "[SCENE] [options]", "100,000 frames and 1,000 create/destroy cycles: memory, images",
                       runSoak},
                  },
                  "\nfrugal-lab also runs every command of frugal (render, report, ...: 'frugal help').\n"};
        for (const CommandEntry& c : frugalProgram().commands) p.commands.push_back(c);
        return p;
    }();
    return program;
}

}  // namespace frugal

int main(int argc, char** argv) { return frugal::runMain(frugal::labProgram(), argc, argv); }
