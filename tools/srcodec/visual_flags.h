// The visual measure's options shared by `compare` and `rd`
// (tools/measure/visual_difference.h).
#pragma once

#include "tools/measure/visual_difference.h"
#include "tools/srcodec/command_line.h"

namespace srcodec {

// --views, --resolution, and --no-visual (`no_visual_help` says what the
// command does without it).
void add_visual_flags(Subcommand& cmd, VisualOptions& options, bool& no_visual, const char* no_visual_help);

}  // namespace srcodec
