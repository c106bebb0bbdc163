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
  bool unsplit_tangles = false;
  bool relax_slivers = true;
  std::string creases = "auto";
  // Set by add_remesh_flags: without --levels, `levels` is fitted to small
  // inputs (RemeshOptions::fit_levels); --max-loss, which --tolerance
  // excludes.
  const Option* levels_option = nullptr;
  Option* max_loss_option = nullptr;
};

// Adds the user's remesh options, shared by remesh, encode and rd: --levels,
// --base-vertices, --threshold (the paper's Eq. 5), --uniform, --max-loss,
// --deepen, --oversample, --scheme, --creases.
void add_remesh_flags(Subcommand& cmd, RemeshFlags& flags);
// Adds the switches that exist for experiments (tools/bench/remesh_experiment):
// --tolerance, --no-fit-surface, --no-untangle, --no-relax-slivers,
// --unsplit-tangles. After add_remesh_flags.
void add_experiment_flags(Subcommand& cmd, RemeshFlags& flags);
StatusOr<RemeshOptions> to_remesh_options(const RemeshFlags& flags);

}  // namespace srcodec
