#include <iostream>
#include <new>

#include <malloc.h>

#include "app/Cli.h"
#include "io/Interrupt.h"
#include "renderer/Backends.h"

int main(int argc, char** argv) {
    frugal::installInterruptHandler();  // before any file is written or any thread started
    // llvmpipe frees and reallocates large scratch memory every frame; glibc's default trim threshold
    // hands it back to the kernel each time. Keeping it cuts llvmpipe's frame time sharply, and a
    // larger M_MMAP_THRESHOLD gained nothing more (docs/gl/README.md).
    mallopt(M_TRIM_THRESHOLD, 512 * 1024 * 1024);
    std::vector<std::string> args(argv + 1, argv + argc);
    int status = frugal::kExitError;
    try {
        status = frugal::runCli(args, std::cout, std::cerr);
    } catch (const std::bad_alloc&) {  // past the checks made up front (renderer/Backends.h)
        std::cerr << "error: " << frugal::outOfMemoryMessage() << "\n";
    }
    frugal::raiseNotedSignal();  // a command stopped by a signal ends by it (io/Interrupt.h)
    return status;
}
