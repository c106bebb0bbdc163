#include "remesh/remesher.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

#include "remesh/base_mesh.h"
#include "remesh/boundary_tips.h"
#include "remesh/components.h"
#include "remesh/geometry.h"
#include "remesh/levels_to_move.h"
#include "remesh/lbg_sites.h"

namespace srcodec {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Splits `total` base vertices over components in proportion to their
// vertex counts, at least min(4, vertices) each. Not by area: what limits a
// component is how many input vertices its Voronoi cells can hold (ogre's
// coarse, large pieces ran out of vertices at level 2 when shared by area).
std::vector<size_t> share_sites(const std::vector<ComponentMesh>& parts, size_t total) {
  size_t sum = 0;
  for (const ComponentMesh& part : parts) sum += part.mesh.positions.size();
  std::vector<size_t> share(parts.size());
  for (size_t c = 0; c < parts.size(); ++c) {
    const size_t n = parts[c].mesh.positions.size();
    const double wanted = static_cast<double>(total) * static_cast<double>(n) / static_cast<double>(sum);
    share[c] = std::min(n, std::max<size_t>(4, static_cast<size_t>(std::llround(wanted))));
  }
  return share;
}

// Voronoi cells flatter than this (their vector area over their area) are
// split across their normals before the base mesh is built (LbgOptions::
// min_flatness): a cell that wraps around a thin part makes base triangles
// that cut through it, and no later level recovers. At 4 levels with the
// default base size, against no splitting (2026-11-28): lionstatue's tail
// 74.94 -> 81.76 dB and 18 + 5 folded triangles -> 0 (11 sites added; the
// base mesh grows by 3, as the collapses keep fewer non-sites);
// bunny_npm 58.81 -> 63.54 dB and 24 + 6 -> 0; beast 68.54 -> 74.28 dB (but
// 159 -> 234 folded); ogre 69.38 -> 70.98 (511 -> 376 folded); armadillo
// 75.02 -> 74.68 (13 more sites, 0 -> 1 folded), stanford-bunny 80.92 ->
// 80.86 (6 -> 9); fandisk, rocker-arm, nefertiti and igea unchanged. 0.5
// also changed fandisk (-0.55 dB) and nefertiti (+1.2); 0.25 missed the
// lion's tail.
constexpr double kMinCellFlatness = 0.4;

// --oversample auto: enough input vertices that the finest uniform level's
// Voronoi cells hold about 8 each. Lloyd needs several vertices per cell to
// move a site anywhere; on stanford-bunny, 3 levels over 1141 base vertices
// reach 62.7 dB with 1.9 vertices per finest cell and 80.3 dB with 7.7.
constexpr double kAutoOversampleRatio = 4.0;
// ... and that almost everywhere, not on average: the fraction of the area
// allowed to stay coarser. ogre's low-poly pieces had 14% empty cells and
// hundreds of folds at level 2 when only the average was checked.
constexpr double kCoarseAreaAllowed = 0.05;

// ... but no more than 4 times the input's vertices or 1M, whichever is
// more: the site selection and the collapses grow with the oversampled count
// (igea at 5 levels: 2.1M vertices, 97 s and 79.5 dB; 537k vertices, 20 s and
// 76.7 dB).
constexpr double kAutoBudgetFactor = 4.0;
constexpr double kAutoBudgetFloor = 1e6;

// The fewest Butterfly/Loop steps (<= 3) after which triangles holding all
// but kCoarseAreaAllowed of the area are kAutoOversampleRatio times smaller
// than the finest uniform level's triangles, within the budget above.
int auto_steps(const TriangleMesh& part, size_t sites, int levels) {
  std::vector<double> areas;
  areas.reserve(part.triangles.size());
  double total = 0.0;
  for (const auto& t : part.triangles) {
    const double a =
        0.5 * (part.positions[t[1]] - part.positions[t[0]]).cross(part.positions[t[2]] - part.positions[t[0]]).norm();
    areas.push_back(a);
    total += a;
  }
  if (!(total > 0.0)) return 0;
  // A closed mesh has about two triangles per vertex.
  const double finest_triangle = total / (2.0 * static_cast<double>(sites) * std::pow(4.0, levels));
  std::sort(areas.begin(), areas.end(), std::greater<double>());
  // The area of the triangle below which all but kCoarseAreaAllowed lies.
  double covered = 0.0, coarse = areas.front();
  for (double a : areas) {
    coarse = a;
    covered += a;
    if (covered >= kCoarseAreaAllowed * total) break;
  }
  int steps = 0;
  double vertices = static_cast<double>(part.positions.size());
  const double budget = std::max(kAutoBudgetFactor * vertices, kAutoBudgetFloor);
  while (steps < 3 && coarse * kAutoOversampleRatio > finest_triangle && 4.0 * vertices <= budget) {
    coarse /= 4.0;
    vertices *= 4.0;
    ++steps;
  }
  return steps;
}
// Below 2 input vertices per output vertex, most cells hold their site only:
// Lloyd cannot move them and new vertices fold the mesh (beast, 2 levels
// without oversampling: 13114 empty cells, 8041 folded triangles, 38.7 dB).
constexpr double kMinUniformRatio = 2.0;
// The smallest default base mesh; a mesh with fewer vertices is its own base
// mesh when the levels are fitted to it.
constexpr size_t kMinDefaultBase = 100;
constexpr size_t kMaxDefaultBase = 4000;
// Oversampled input vertices per finest-level vertex that the default base
// size may go down to once the oversampling is done (remesh()).
constexpr double kSupportedRatio = 6.5;

}  // namespace

size_t default_base_vertices(size_t input_vertices, size_t components, int levels) {
  const double v = static_cast<double>(input_vertices);
  // As many base vertices as the oversampling budget allows with about 8
  // input vertices per finest-level vertex, and no more than 1 per 24 input
  // vertices. Measured on stanford-bunny: 124 base vertices and 4 levels give
  // 58.8 dB, 537 give 74.2 dB (3 levels over 1559: 80.6 dB); on armadillo
  // (14587 vertices), 228 base vertices (the old 1 per 64) give 65.5 dB at 4
  // levels, 488 (this rule) 69.0 dB, 600 72.8 dB. Fewer input vertices per
  // finest vertex hurt: 6 instead of 8 took the bunny from 79.3 to 71.8 dB and
  // nefertiti from 75.5 to 71.5 dB (3.2 and 4.8 oversampled input vertices
  // per finest vertex), though armadillo gained (72.0 dB).
  const double budget = std::max(kAutoBudgetFactor * v, kAutoBudgetFloor);
  const double by_budget = budget / (8.0 * std::pow(4.0, std::max(levels, 0)));
  const double base = std::min(v / 24.0, by_budget);
  return std::clamp<size_t>(static_cast<size_t>(std::llround(base)), std::max<size_t>(kMinDefaultBase, 4 * components),
                            kMaxDefaultBase);
}

StatusOr<SemiRegularMesh> remesh(const TriangleMesh& mesh, const RemeshOptions& options, RemeshReport* report) {
  RemeshReport local;
  RemeshReport& rep = report ? *report : local;
  rep = RemeshReport{};
  auto progress = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  if (options.levels < 0 || options.levels > 12)
    return invalid_argument("remesh: " + std::to_string(options.levels) + " levels asked; use 0 to 12");
  if (!(options.tolerance_db >= 0.0 && options.tolerance_db < 400.0))
    return invalid_argument("remesh: tolerance " + std::to_string(options.tolerance_db) +
                            " dB; use 0 (off) or a PSNR below 400 dB");
  if (!(options.max_loss_db >= 0.0 && options.max_loss_db <= 60.0))
    return invalid_argument("remesh: max loss " + std::to_string(options.max_loss_db) +
                            " dB; use 0 (off) or more, up to 60");
  if (options.max_loss_db > 0.0 && (!options.uniform || options.tolerance_db > 0.0))
    return invalid_argument("remesh: the measured coarsening (max loss) undoes splits of the uniform refinement; ask "
                            "for uniform refinement without a tolerance or threshold");
  if (!(options.deepen_fraction >= 0.0 && options.deepen_fraction <= 1.0))
    return invalid_argument("remesh: deepen fraction " + std::to_string(options.deepen_fraction) +
                            "; use 0 (off) up to 1");
  if (options.deepen_fraction > 0.0 && options.levels >= 12)
    return invalid_argument("remesh: deepening adds a level to the " + std::to_string(options.levels) +
                            " asked, past the 12 that .srm files hold; ask for at most 11");
  if (options.deepen_fraction > 0.0 && !(options.max_loss_db > 0.0))
    return invalid_argument("remesh: deepening (split the worst triangles once more) is part of the measured "
                            "coarsening; ask for a max loss too");
  if (options.oversample < -1 || options.oversample > 3)
    return invalid_argument("remesh: oversample " + std::to_string(options.oversample) + "; use auto or 0 to 3");
  if (mesh.triangles.empty()) return invalid_mesh("remesh: the mesh has no triangles");
  const bool fit = options.fit_levels && options.base_vertices == 0;
  if (fit && mesh.positions.size() < kMinDefaultBase) {
    RemeshOptions whole = options;
    whole.fit_levels = false;
    whole.levels = 0;
    whole.oversample = 0;
    whole.base_vertices = 0;
    // Cutting non-manifold spots may have duplicated some vertices.
    SRCODEC_ASSIGN_OR_RETURN(std::vector<ComponentMesh> pieces, split_into_manifold_components(mesh));
    for (const ComponentMesh& piece : pieces) whole.base_vertices += piece.mesh.positions.size();
    progress("the input has " + std::to_string(mesh.positions.size()) + " vertices, fewer than the smallest default " +
             "base mesh (" + std::to_string(kMinDefaultBase) + "): it is the base mesh, with no levels");
    return remesh(mesh, whole, report);
  }

  SRCODEC_ASSIGN_OR_RETURN(std::vector<ComponentMesh> parts, split_into_manifold_components(mesh));
  rep.components = parts.size();
  // Each component's share of the base is capped at its own vertex count
  // (share_sites), whatever the oversampling: a larger request would get
  // fewer base vertices than asked, with no word.
  size_t input_vertices = 0;
  for (const ComponentMesh& part : parts) input_vertices += part.mesh.positions.size();
  if (options.base_vertices > input_vertices)
    return invalid_argument("remesh: " + std::to_string(options.base_vertices) +
                            " base vertices asked but the mesh has only " + std::to_string(input_vertices) +
                            " vertices, and base vertices are taken among its own: ask for at most " +
                            std::to_string(input_vertices) + " (--base-vertices)");
  size_t base_total = options.base_vertices > 0
                          ? options.base_vertices
                          : default_base_vertices(mesh.positions.size(), parts.size(), options.levels);
  std::vector<size_t> share = share_sites(parts, base_total);

  // Oversampling per component: each gets the steps its own share needs, so
  // a small piece with few vertices is not starved by a large one.
  auto start = std::chrono::steady_clock::now();
  for (size_t c = 0; c < parts.size(); ++c) {
    const int steps = options.oversample >= 0 ? options.oversample
                                              : auto_steps(parts[c].mesh, share[c], options.levels);
    SRCODEC_ASSIGN_OR_RETURN(parts[c].mesh, oversample(parts[c].mesh, options.scheme, steps));
    rep.component_oversample_steps.push_back(steps);
    rep.oversample_steps = std::max(rep.oversample_steps, steps);
    rep.oversampled_vertices += parts[c].mesh.positions.size();
  }
  rep.seconds_oversample = seconds_since(start);
  if (rep.oversample_steps > 0)
    progress("oversampled (up to " + std::to_string(rep.oversample_steps) + " steps per component): " +
             std::to_string(rep.oversampled_vertices) + " vertices, " + std::to_string(rep.seconds_oversample) + " s");
  if (options.base_vertices == 0) {
    // The default base size was planned on the oversampling budget; a small
    // input that got all three steps may hold more than planned: as many base
    // vertices as kSupportedRatio oversampled vertices per finest vertex
    // allow, still at most one per 24 input vertices. On armadillo (14587
    // vertices, 933442 oversampled) this takes the base from 488 to 561
    // vertices at 4 levels (488 gave 69.0 dB, 560 74.5 dB, 608 71.5 dB).
    // 6 instead of 6.5 also raised nefertiti's base, from 488 to 521, and
    // took it from 75.5 to 71.8 dB (520 gave 76.4 dB: the quality swings by
    // a few dB with the base size; measured 2026-11-28).
    const double supported = std::min(static_cast<double>(mesh.positions.size()) / 24.0,
                                       static_cast<double>(rep.oversampled_vertices) /
                                           (kSupportedRatio * std::pow(4.0, options.levels)));
    const size_t raised = std::min<size_t>(static_cast<size_t>(std::llround(supported)), kMaxDefaultBase);
    if (raised > base_total) {
      for (size_t c = 0; c < parts.size(); ++c)
        share[c] = std::min(parts[c].mesh.positions.size(),
                            static_cast<size_t>(std::llround(static_cast<double>(share[c]) * raised / base_total)));
      base_total = raised;
      progress("default base size raised to " + std::to_string(base_total) +
               " vertices: the oversampled input holds more vertices than planned");
    }
  }
  const double finest = static_cast<double>(base_total) * std::pow(4.0, options.levels);
  const bool too_few_for_uniform = static_cast<double>(rep.oversampled_vertices) < kMinUniformRatio * finest;
  const bool too_few_for_levels = options.uniform && options.levels > 0 && too_few_for_uniform;
  if (too_few_for_levels && fit) {
    RemeshOptions fewer = options;
    fewer.levels = options.levels - 1;
    progress(std::to_string(options.levels) + " levels need about " +
             std::to_string(static_cast<size_t>(kMinUniformRatio * finest)) + " input vertices, the input has " +
             std::to_string(rep.oversampled_vertices) + (rep.oversample_steps > 0 ? " after oversampling" : "") +
             ": trying " + std::to_string(fewer.levels));
    return remesh(mesh, fewer, report);
  }
  if (too_few_for_levels)
    return invalid_argument(
        "remesh: " + std::to_string(options.levels) + " uniform levels over " + std::to_string(base_total) +
        " base vertices make about " + std::to_string(static_cast<size_t>(finest)) + " vertices, but the input has " +
        std::to_string(rep.oversampled_vertices) + (rep.oversample_steps > 0 ? " after oversampling" : "") +
        "; the Voronoi cells need at least " + std::to_string(static_cast<int>(kMinUniformRatio)) +
        " input vertices per output vertex: oversample more (--oversample, up to 3), or ask for fewer levels or fewer "
        "base vertices (--base-vertices)");
  if (base_total > rep.oversampled_vertices)
    return invalid_argument("remesh: " + std::to_string(base_total) + " base vertices asked but the mesh has only " +
                            std::to_string(rep.oversampled_vertices) + " vertices" +
                            (rep.oversample_steps > 0 ? " after oversampling" : "") + "; ask for at most " +
                            std::to_string(rep.oversampled_vertices / 4) + " (--base-vertices) or oversample more");

  // Per component: sites, then base mesh; both joined into one domain.
  TriangleMesh input;
  BaseMesh base;
  double sites_s = 0.0, base_s = 0.0;
  for (size_t c = 0; c < parts.size(); ++c) {
    const TriangleMesh& part = parts[c].mesh;
    auto t0 = std::chrono::steady_clock::now();
    VoronoiCells cells;
    if (share[c] >= part.positions.size()) {
      for (size_t v = 0; v < part.positions.size(); ++v) {
        cells.sites.push_back(static_cast<int32_t>(v));
        cells.cell_of.push_back(static_cast<int32_t>(v));
      }
    } else {
      LbgOptions lbg;
      lbg.target_sites = share[c];
      lbg.min_flatness = kMinCellFlatness;
      LbgReport lbg_report;
      SRCODEC_ASSIGN_OR_RETURN(cells, lbg_sites(part, lbg, &lbg_report));
      for (const auto& round : lbg_report.rounds) rep.curled_sites += round.curled_splits;
      BoundaryTipOptions tips;
      tips.reach = boundary_tip_reach(part, share[c]);
      rep.tip_sites += add_boundary_tip_sites(part, tips, &cells);
    }
    sites_s += seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    BaseMeshReport base_report;
    auto built = build_base_mesh(part, cells.sites, cells.cell_of, &base_report);
    if (!built.ok()) return built.status().with_context("component " + std::to_string(c));
    base_s += seconds_since(t0);
    rep.promoted_vertices += base_report.promoted_vertices;

    const int32_t input_offset = static_cast<int32_t>(input.positions.size());
    const int32_t face_offset = static_cast<int32_t>(base.mesh.triangles.size());
    append_mesh(input, part);
    append_mesh(base.mesh, built->mesh);
    for (int32_t v : built->input_vertex) base.input_vertex.push_back(v + input_offset);
    for (ParamPoint p : built->param) {
      p.face += face_offset;
      base.param.push_back(p);
    }
  }
  rep.seconds_sites = sites_s;
  rep.seconds_base = base_s;
  rep.base_vertices = base.mesh.positions.size();
  progress("base mesh: " + std::to_string(rep.base_vertices) + " vertices (" + std::to_string(rep.curled_sites) +
           " sites added in curled cells, " + std::to_string(rep.tip_sites) + " at the tips of narrow holes, " +
           std::to_string(rep.promoted_vertices) + " kept by the collapses), " +
           std::to_string(base.mesh.triangles.size()) + " triangles; sites " + std::to_string(sites_s) +
           " s, collapses " + std::to_string(base_s) + " s");

  start = std::chrono::steady_clock::now();
  RefineOptions refine_options;
  refine_options.levels = options.levels;
  refine_options.threshold = options.threshold;
  refine_options.uniform = options.uniform;
  // The threshold judged on a uniform refinement where the input supports
  // one: at 5 levels, against the paper's order, armadillo eps 4 at 99% of
  // uniform's triangles 69.36 -> 71.82 dB (uniform 72.20), nefertiti eps 16
  // at 64% 73.06 -> 74.67 dB (uniform 75.61), the bunny eps 16 at 49%
  // 68.41 -> 69.52 dB (uniform 67.14; both before boundary sites kept to
  // their loops, which took them to 73.49 and 74.88), igea eps 16 at 58%
  // 80.08 -> 79.28 dB (uniform 86.45; Eq. 5 is not geometric).
  refine_options.threshold_after_uniform = !options.uniform && options.levels > 0 && !too_few_for_uniform;
  rep.threshold_after_uniform = refine_options.threshold_after_uniform;
  if (!options.uniform && options.levels > 0 && too_few_for_uniform)
    progress("threshold: the input is too sparse for " + std::to_string(options.levels) +
             " uniform levels; Eq. 5 decides level by level (the paper's order)");
  if (options.tolerance_db > 0.0)
    refine_options.tolerance = bounding_box_diagonal(mesh.positions) * std::pow(10.0, -options.tolerance_db / 20.0);
  refine_options.max_lloyd_iterations = options.max_lloyd_iterations;
  refine_options.follow_detours = options.follow_detours;
  refine_options.progress = options.progress;
  SRCODEC_ASSIGN_OR_RETURN(RefineResult refined, refine(input, base, refine_options, &rep.levels));
  rep.seconds_refine = seconds_since(start);

  std::vector<Eigen::Vector3d> positions = std::move(refined.positions);
  for (size_t b = 0; b < base.mesh.positions.size(); ++b) base.mesh.positions[b] = positions[b];  // Lloyd moved them
  const int32_t levels = static_cast<int32_t>(rep.levels.size());
  if (options.fit_surface && levels > 0) {
    const LevelsToMove moving = levels_to_move(refined.hierarchy, levels, base.mesh.positions.size(), positions.size());
    rep.fit = fit_to_surface(mesh, input, moving.triangles, moving.fixed, &positions);
    progress("fit: " + std::to_string(rep.fit.moved) + " vertices moved off the input (mean " +
             std::to_string(rep.fit.mean_offset) + "), " + std::to_string(rep.fit.refused) +
             " moves undone where a triangle would turn, fold or pleat; then " +
             std::to_string(rep.fit.folded_by_nearest_input) + " folded (recount), " + std::to_string(rep.fit.pleats) +
             " pleats, " + std::to_string(rep.fit.seconds) + " s");
  }
  SemiRegularMesh out{std::move(base.mesh), std::move(refined.hierarchy), std::move(positions), levels};
  // The input's sides, search and components, built once for every
  // untangling and unsplitting pass below.
  std::unique_ptr<UntangleInput> untangle_input;
  auto untangle_data = [&]() -> const UntangleInput& {
    if (!untangle_input) untangle_input = std::make_unique<UntangleInput>(input);
    return *untangle_input;
  };
  // The untangling (last; with --max-loss also before the coarsening, so
  // that its loss is judged against the untangled full refinement).
  auto untangle_out = [&](SemiRegularMesh* m, const UntangleOptions& untangle_options) {
    const LevelsToMove tangled = levels_to_move(m->hierarchy, m->levels, m->base.positions.size(), m->positions.size());
    const auto set_up = std::chrono::steady_clock::now();
    UntangleReport r = untangle(untangle_data(), tangled.triangles, tangled.fixed, &m->positions, untangle_options);
    r.seconds = seconds_since(set_up);  // with the input's set-up, the first time
    const TangleCount &was = r.before, &now = r.after;
    auto counts = [](size_t folded, size_t pleats) {
      return std::to_string(folded) + " folded, " + std::to_string(pleats) + " pleats";
    };
    progress(std::string(untangle_options.wide_candidates > 0 ? "untangle (wide search): " : "untangle: ") +
             std::to_string(r.moved) + " moves (" + std::to_string(r.joint_moved) + " joint) in " +
             std::to_string(r.rounds) + " rounds; finest level " + counts(was.folded, was.pleats) + " -> " + counts(now.folded, now.pleats) +
             "; coarser levels " + counts(was.coarser_folded, was.coarser_pleats) + " -> " +
             counts(now.coarser_folded, now.coarser_pleats) + ", " + std::to_string(r.seconds) + " s");
    if (rep.untangle.rounds == 0) rep.untangle.before = r.before;
    rep.untangle.after = r.after;
    rep.untangle.moved += r.moved;
    rep.untangle.joint_moved += r.joint_moved;
    rep.untangle.rounds += r.rounds;
    rep.untangle.seconds += r.seconds;
  };
  const bool untangling = options.fit_surface && options.untangle && levels > 0;
  if (untangling && options.max_loss_db > 0.0) untangle_out(&out, {});
  if (options.max_loss_db > 0.0 && levels > 0) {
    CoarseningOptions coarsening;
    coarsening.max_loss_db = options.max_loss_db;
    coarsening.refit = options.fit_surface;  // --no-fit-surface keeps the sites where they are
    coarsening.deepen_fraction = options.deepen_fraction;
    SRCODEC_ASSIGN_OR_RETURN(out, coarsen_by_measured_error(mesh, input, out, coarsening, &rep.coarsening));
    // The level reports: the last one's splits are those kept (fewer
    // levels when none is).
    rep.levels.resize(static_cast<size_t>(out.levels));
    for (size_t l = 0; l < rep.levels.size(); ++l) rep.levels[l].level = static_cast<int>(l) + 1;
    if (out.levels > levels) {  // deepened: the triangles chosen, and of both last levels, those split in the end
      auto split_at = [&](int32_t level) {
        size_t n = 0;
        for (const TriangleHierarchy::Node& node : out.hierarchy.nodes())
          n += node.level == level && node.first_child >= 0;
        return n;
      };
      RefineLevelReport& asked = rep.levels[static_cast<size_t>(levels) - 1];
      const size_t kept = split_at(levels - 1);
      asked.within_tolerance = asked.split > kept ? asked.split - kept : 0;
      asked.split = kept;
      rep.levels.back().selected = rep.coarsening.deepened;
      rep.levels.back().split = split_at(levels);
    }
    if (out.levels == levels) {
      RefineLevelReport& last = rep.levels.back();
      last.within_tolerance = rep.coarsening.undone;
      last.split = rep.coarsening.candidates - rep.coarsening.undone;
    }
    const std::string deepened =
        rep.coarsening.deepened > 0 ? std::to_string(rep.coarsening.deepened) + " triangles of level " +
                                          std::to_string(levels) + " split once more; " : "";
    progress("measured coarsening: " + deepened + std::to_string(rep.coarsening.undone) + " of " +
             std::to_string(rep.coarsening.candidates) + " splits of level " +
             (rep.coarsening.deepened > 0 ? std::to_string(levels - 1) + " and " + std::to_string(levels)
                                          : std::to_string(levels - 1)) +
             " undone, " + std::to_string(rep.coarsening.triangles_before) + " -> " +
             std::to_string(rep.coarsening.triangles_after) + " triangles, estimated loss " +
             std::to_string(rep.coarsening.estimated_loss_db) + " dB (" + std::to_string(rep.coarsening.kept_for_folds) +
             " kept where undoing them folded or pleated; " + std::to_string(rep.coarsening.refit) +
             " vertices fitted again, " + std::to_string(rep.coarsening.passes) + " pass(es), " +
             std::to_string(rep.coarsening.estimated_loss_before_refit_db) + " dB before the first refit); then " +
             std::to_string(rep.coarsening.folds.folded_by_nearest_input) + " folded (recount), " +
             std::to_string(rep.coarsening.folds.pleats) + " pleats, " + std::to_string(rep.coarsening.seconds) + " s");
  }
  if (untangling && out.levels > 0) untangle_out(&out, {});
  // Where triangles stay tangled: splits of the level above the finest
  // undone around them (remesh/unsplit_tangles.h) and the untangling run
  // again. First around the finest level's tangled triangles; then also at
  // the corners of the coarser levels' (a corner with no finest triangles
  // around it moves as its own levels ask). A pass is kept when it leaves
  // fewer tangled triangles, all levels counted; up to 4 passes of each
  // kind. (Fitting the corners left whole to the input again, as the
  // measured coarsening does, cost ogre 9 s a pass and 0.1 dB.)
  const bool unsplitting = options.unsplits() && out.levels > 0;
  for (int kind = 0; unsplitting && kind < 2; ++kind)
    for (int pass = 0; pass < 4 && rep.untangle.after.total() > 0; ++pass) {
      UnsplitOptions unsplit;
      unsplit.coarser = kind == 1;
      UnsplitReport u;
      SRCODEC_ASSIGN_OR_RETURN(SemiRegularMesh next, unsplit_tangles(untangle_data().side_at(), out, unsplit, &u));
      rep.unsplit.seconds += u.seconds;
      if (u.stars == 0) break;
      const UntangleReport untangled = rep.untangle;
      untangle_out(&next, {});
      const bool kept = rep.untangle.after.total() < untangled.after.total();
      progress("unsplit" + std::string(unsplit.coarser ? " (coarser levels too)" : "") + ": " +
               std::to_string(u.stars) + " stars of level " + std::to_string(out.levels - 1) + " left whole (" +
               std::to_string(u.undone) + " splits undone) and untangled again: tangled triangles, all levels, " +
               std::to_string(untangled.after.total()) + " -> " + std::to_string(rep.untangle.after.total()) +
               (kept ? ", kept" : ", not kept"));
      if (!kept) {
        rep.untangle = untangled;
        break;
      }
      out = std::move(next);
      ++rep.unsplit.passes;
      rep.unsplit.stars += u.stars;
      rep.unsplit.undone += u.undone;
      if (static_cast<size_t>(out.levels) == rep.levels.size()) {
        RefineLevelReport& last = rep.levels.back();
        last.split -= std::min(last.split, u.undone);
      }
    }
  // Last, where triangles stay tangled: one more untangling that also tries,
  // for each free vertex, the 128 input vertices nearest it and as many
  // nearest its neighbours' centroid (UntangleOptions::wide_candidates). At
  // the defaults, against none (folded + pleats, finest + coarser; PSNR at
  // 1M samples, seeds 1 and 2): beast 14 + 14, 1 + 22 -> 8 + 12, 0 + 21 at
  // 78.32 -> 78.33 dB; beast_tri 8 + 11, 1 + 17 -> 5 + 10, 0 + 15 at 75.66 ->
  // 75.52; ogre 4 + 13, 1 + 23 -> 3 + 12, 0 + 23 at 75.52 -> 75.55. The same
  // search in every pass left fewer finest folds (6, 3, 2) but moved far
  // more vertices: beast 78.08, beast_tri 75.13, ogre 76.13 dB; 32 each
  // instead of 128 left beast 12 + 13 (twenty-ninth session).
  if (untangling && out.levels > 0 && rep.untangle.after.total() > 0) {
    UntangleOptions wide;
    wide.wide_candidates = 128;
    untangle_out(&out, wide);
  }
  // The levels' triangles, for the sliver relaxation and for the places of
  // the tangles left; it moves vertices only, so both see the same levels.
  const bool relaxing = options.relax_slivers && options.fit_surface && out.levels > 0;
  const bool placing = rep.untangle.rounds > 0 && rep.untangle.after.total() > 0;
  const LevelsToMove final_levels =
      relaxing || placing ? levels_to_move(out.hierarchy, out.levels, out.base.positions.size(), out.positions.size())
                          : LevelsToMove{};
  // No triangle of any level folds or pleats more or less (relax_slivers
  // moves no vertex of a tangled triangle and refuses moves that tangle
  // one), so the untangling's counts stay the output's.
  if (relaxing) {
    rep.slivers = relax_slivers(untangle_data().side_at(), final_levels.triangles[static_cast<size_t>(out.levels)],
                                final_levels.triangles[static_cast<size_t>(out.levels) - 1], final_levels.fixed,
                                &out.positions);
    progress("slivers: " + std::to_string(rep.slivers.moved) + " moves; finest triangles of quality below " +
             std::to_string(SliverRelaxOptions{}.poor_quality).substr(0, 4) + ": " +
             std::to_string(rep.slivers.poor_before) + " -> " + std::to_string(rep.slivers.poor_after) + ", " +
             std::to_string(rep.slivers.seconds) + " s");
  }
  if (placing)
    rep.tangled_places = tangled_places(untangle_data(), final_levels.triangles, out.positions,
                                        kTangledPlaceReach * bounding_box_diagonal(mesh.positions));
  return out;
}

}  // namespace srcodec
