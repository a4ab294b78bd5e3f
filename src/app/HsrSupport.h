// The command-line side of the hidden-surface modes (paper 003, src/hsr/Plan.h), shared by render,
// bench and diff: the --hsr option.
#pragma once

#include <optional>
#include <string>

#include "app/Options.h"
#include "hsr/Plan.h"

namespace frugal {

// --hsr MODE. False when `flag` is not --hsr; a usage error names the modes.
bool parseHsrOption(const std::string& flag, ArgCursor& cursor, hsr::Mode& mode);

// The option's help lines.
const char* hsrOptionHelp();

}  // namespace frugal
