// The command-line side of the hidden-surface modes (paper 003, src/hsr/Plan.h), shared by render,
// bench and diff: the --hsr option, and one frame's plan with its JSON.
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "app/Options.h"
#include "hsr/Plan.h"

namespace frugal {

// --hsr MODE. False when `flag` is not --hsr; a usage error names the modes.
bool parseHsrOption(const std::string& flag, ArgCursor& cursor, hsr::Mode& mode);

// The option's help lines.
const char* hsrOptionHelp();

// {"mode", "polygons", "zbuffered_polygons", "zbuffered_share", "draws", "plan_ms"} of one frame's plan.
nlohmann::json hsrJson(hsr::Mode mode, const hsr::PlanStats& stats);

}  // namespace frugal
