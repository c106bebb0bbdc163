#include "tools/srcodec/visual_flags.h"

namespace srcodec {

void add_visual_flags(Subcommand& cmd, VisualOptions& options, bool& no_visual, const char* no_visual_help) {
  cmd.option("--views", options.views, "Views the visual measure renders of each mesh, spread around the reference")
      .range(kMinVisualViews, kMaxVisualViews)
      .show_default();
  cmd.option("--resolution", options.resolution, "Pixels per side of each view")
      .range(kMinVisualResolution, kMaxVisualResolution)
      .show_default();
  cmd.flag("--no-visual", no_visual, no_visual_help);
}

}  // namespace srcodec
