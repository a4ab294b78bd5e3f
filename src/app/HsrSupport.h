// The command-line side of the hidden-surface modes (paper 003, src/hsr/Plan.h), shared by render,
// bench, diff and cull-report: the --hsr flag.
#pragma once

#include <string>

#include "app/Flags.h"
#include "hsr/Plan.h"

namespace frugal {

// --hsr MODE into `mode`; `help` replaces the table of modes render prints.
Flag hsrFlag(hsr::Mode& mode, std::string help = {});

}  // namespace frugal
