#include <malloc.h>

#include <iostream>

#include "app/Cli.h"

int main(int argc, char** argv) {
    // llvmpipe frees and reallocates large scratch memory every frame; glibc's default trim threshold
    // hands it back to the kernel each time. Keeping it halves frame time: bunny 800×600 on
    // egl-surfaceless 29.4 → 13.1 ms here (`frugal bench render`). A larger M_MMAP_THRESHOLD
    // measured no further gain.
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
    std::vector<std::string> args(argv + 1, argv + argc);
    return frugal::runCli(args, std::cout, std::cerr);
}
