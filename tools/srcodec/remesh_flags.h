// The remesh options shared by `remesh` and `encode`.
#pragma once

#include <string>

#include "format/status.h"
#include "remesh/remesher.h"
#include "tools/srcodec/command_line.h"

namespace srcodec {

struct RemeshFlags {
  std::string oversample = "auto", scheme = "butterfly";
  int levels = 4;
  size_t base_vertices = 0;
  double threshold = -1.0;
  bool uniform = false;
  double tolerance_db = 0.0;
  double max_loss_db = 0.0;
  double deepen_fraction = 0.0;
  bool fit_surface = true;
  bool untangle = true;
  bool unsplit_tangles = true;
  bool follow_detours = false;
  bool relax_slivers = true;
  // Set by add_remesh_flags: without --levels, `levels` is fitted to small
  // inputs (RemeshOptions::fit_levels).
  const Option* levels_option = nullptr;
};

// Adds --levels, --base-vertices, --threshold, --uniform, --tolerance, --max-loss, --deepen, --no-fit-surface,
// --no-untangle, --keep-tangled-splits (or --unsplit-tangles), --follow-detours, --no-relax-slivers,
// --oversample, --scheme.
// With `for_coding` (encode, rd) the unsplitting is off unless
// --unsplit-tangles asks for it; remesh has it on, --keep-tangled-splits
// turns it off.
void add_remesh_flags(Subcommand& cmd, RemeshFlags& flags, bool for_coding = false);
StatusOr<RemeshOptions> to_remesh_options(const RemeshFlags& flags);

}  // namespace srcodec
