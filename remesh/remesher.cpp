#include "remesh/remesher.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>

#include "remesh/base_creases.h"
#include "remesh/base_mesh.h"
#include "remesh/boundary_tips.h"
#include "remesh/components.h"
#include "remesh/features.h"
#include "remesh/geometry.h"
#include "remesh/levels_to_move.h"
#include "remesh/lbg_sites.h"
#include "remesh/memory_budget.h"

namespace srcodec {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Splits `total` base vertices over components in proportion to their
// vertex counts, at least min(4, vertices) each. Not by area: what limits a
// component is how many input vertices its Voronoi cells can hold (coarse,
// large pieces run out of vertices when shared by area).
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
// that cut through it, and no later level recovers. The value is the one
// that catches thin tails without changing smooth meshes
// (docs/remesh_design.md, "Constants of remesh/ and what they measure").
constexpr double kMinCellFlatness = 0.4;

// --oversample auto: enough input vertices that the finest uniform level's
// Voronoi cells hold about 8 each. Lloyd needs several vertices per cell to
// move a site anywhere.
constexpr double kAutoOversampleRatio = 4.0;
// ... and that almost everywhere, not on average: the fraction of the area
// allowed to stay coarser: low-poly pieces of a mesh leave empty cells and
// folds when only the average is checked.
constexpr double kCoarseAreaAllowed = 0.05;

// ... but no more than 4 times the input's vertices or 1M, whichever is
// more: the site selection and the collapses grow with the oversampled count
// faster than the quality does.
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
// Lloyd cannot move them and new vertices fold the mesh.
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
  // vertices: a larger base mesh stretches the parameterization less, and
  // fewer input vertices per finest vertex leave Lloyd too little to move.
  const double budget = std::max(kAutoBudgetFactor * v, kAutoBudgetFloor);
  const double by_budget = budget / (8.0 * std::pow(4.0, std::max(levels, 0)));
  const double base = std::min(v / 24.0, by_budget);
  return std::clamp<size_t>(static_cast<size_t>(std::llround(base)), std::max<size_t>(kMinDefaultBase, 4 * components),
                            kMaxDefaultBase);
}

namespace {

// Checks what remesh() is asked before any work.
Status check_options(const RemeshOptions& options) {
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
  return ok_status();
}

// The steps of remesh(), in order, over one input; each step a member.
class Remesher {
 public:
  Remesher(const TriangleMesh& mesh, const RemeshOptions& options, RemeshReport& rep)
      : mesh_(mesh), options_(options), rep_(rep) {}

  // An input with fewer vertices than the smallest default base mesh is its
  // own base mesh, with no levels (RemeshOptions::fit_levels).
  StatusOr<SemiRegularMesh> whole_input_as_base(RemeshReport* report) const;
  // Components, their share of the base vertices and their oversampling.
  Status split_and_oversample();
  // Per component: the oversampling steps for `levels` (`asked` >= 0: those).
  std::vector<int> oversampling_steps(int levels, int asked) const;
  uint64_t oversampled_vertices(const std::vector<int>& steps) const;
  // The memory the oversampled input will take against what the machine
  // can give (RemeshOptions::memory_limit), before any of it is taken.
  Status check_memory(const std::vector<int>& steps) const;
  // The default base size, raised where the oversampled input holds more
  // vertices than planned.
  void raise_default_base();
  // Too few input vertices for the levels asked: fewer levels (when they
  // were not asked for), or an error that says what would work.
  StatusOr<bool> enough_for_levels(bool fit);
  StatusOr<SemiRegularMesh> with_fewer_levels(RemeshReport* report) const;
  // Per component: sites, then base mesh; both joined into one domain.
  Status build_base();
  // Component c's sites and cells (LBG, curled cells, boundary tips).
  StatusOr<VoronoiCells> sites_of(size_t c);
  // The paper's refinement (remesh/refine.h), then the fit.
  Status refine_levels();
  void fit();
  // Our repairs and adaptivity after the refinement, on `out`.
  void untangle_out(SemiRegularMesh* m, const UntangleOptions& untangle_options);
  Status coarsen(SemiRegularMesh* out, int32_t levels);
  Status unsplit(SemiRegularMesh* out);
  void relax_and_place(SemiRegularMesh* out);

  StatusOr<SemiRegularMesh> run(RemeshReport* report, bool fit_levels);

 private:
  void progress(RemeshProgress p) const {
    if (!options_.progress) return;
    if (!p.report) p.report = &rep_;
    options_.progress(p);
  }
  const UntangleInput& untangle_data() {
    if (!untangle_input_) untangle_input_ = std::make_unique<UntangleInput>(input_);
    return *untangle_input_;
  }

  const TriangleMesh& mesh_;
  const RemeshOptions& options_;
  RemeshReport& rep_;
  std::vector<ComponentMesh> parts_;
  std::vector<BaseMeshCreases> creases_;  // per component, as RemeshOptions::creases asks
  // Fills creases_ (RemeshOptions::creases) and the report's
  // crease_edge_share: with kAuto all the components' creases or none, as
  // the mesh's followable curves take kAutoCreaseEdgeShare of its base's
  // edges or not.
  void choose_creases();
  std::vector<size_t> share_;
  size_t base_total_ = 0;
  double finest_ = 0.0;
  bool too_few_for_uniform_ = false;
  TriangleMesh input_;  // the oversampled components, joined
  BaseMesh base_;
  RefineResult refined_;
  std::vector<Eigen::Vector3d> positions_;
  // The input's sides, search and components, built once for every
  // untangling and unsplitting pass.
  std::unique_ptr<UntangleInput> untangle_input_;
};

StatusOr<SemiRegularMesh> Remesher::whole_input_as_base(RemeshReport* report) const {
  RemeshOptions whole = options_;
  whole.fit_levels = false;
  whole.levels = 0;
  whole.oversample = 0;
  whole.base_vertices = 0;
  // Cutting non-manifold spots may have duplicated some vertices.
  SRCODEC_ASSIGN_OR_RETURN(std::vector<ComponentMesh> pieces, split_into_manifold_components(mesh_));
  for (const ComponentMesh& piece : pieces) whole.base_vertices += piece.mesh.positions.size();
  RemeshProgress p;
  p.step = RemeshStep::kWholeInputIsBase;
  p.vertices = mesh_.positions.size();
  p.min_base_vertices = kMinDefaultBase;
  progress(p);
  return remesh(mesh_, whole, report);
}

Status Remesher::split_and_oversample() {
  const auto split_start = std::chrono::steady_clock::now();
  SRCODEC_ASSIGN_OR_RETURN(parts_, split_into_manifold_components(mesh_));
  rep_.components = parts_.size();
  // Each component's share of the base is capped at its own vertex count
  // (share_sites), whatever the oversampling: a larger request would get
  // fewer base vertices than asked, with no word.
  size_t input_vertices = 0;
  for (const ComponentMesh& part : parts_) input_vertices += part.mesh.positions.size();
  RemeshProgress split;
  split.step = RemeshStep::kComponents;
  split.vertices = input_vertices;
  split.seconds = seconds_since(split_start);
  progress(split);
  if (options_.base_vertices > input_vertices)
    return invalid_argument("remesh: " + std::to_string(options_.base_vertices) +
                            " base vertices asked but the mesh has only " + std::to_string(input_vertices) +
                            " vertices, and base vertices are taken among its own: ask for at most " +
                            std::to_string(input_vertices) + " (--base-vertices)");
  base_total_ = options_.base_vertices > 0
                    ? options_.base_vertices
                    : default_base_vertices(mesh_.positions.size(), parts_.size(), options_.levels);
  share_ = share_sites(parts_, base_total_);

  // Oversampling per component: each gets the steps its own share needs, so
  // a small piece with few vertices is not starved by a large one.
  const std::vector<int> steps = oversampling_steps(options_.levels, options_.oversample);
  SRCODEC_RETURN_IF_ERROR(check_memory(steps));
  const auto start = std::chrono::steady_clock::now();
  choose_creases();
  for (size_t c = 0; c < parts_.size(); ++c) {
    SRCODEC_ASSIGN_OR_RETURN(parts_[c].mesh,
                             oversample(parts_[c].mesh, options_.scheme, steps[c], &creases_[c].edges));
    rep_.component_oversample_steps.push_back(steps[c]);
    rep_.oversample_steps = std::max(rep_.oversample_steps, steps[c]);
    rep_.oversampled_vertices += parts_[c].mesh.positions.size();
  }
  rep_.seconds_oversample = seconds_since(start);
  if (rep_.oversample_steps > 0) {
    RemeshProgress p;
    p.step = RemeshStep::kOversampled;
    p.seconds = rep_.seconds_oversample;
    progress(p);
  }
  return ok_status();
}

void Remesher::choose_creases() {
  creases_.assign(parts_.size(), BaseMeshCreases{});
  if (options_.creases == CreaseMode::kIgnore) return;
  double followed = 0.0, base_vertices = 0.0;
  for (size_t c = 0; c < parts_.size(); ++c) {
    BaseCreaseOptions keep;
    keep.base_vertices = share_[c];
    const Features features = detect_features(parts_[c].mesh);
    followed += followable_base_edges(parts_[c].mesh, features, keep);
    base_vertices += static_cast<double>(share_[c]);
    creases_[c] = base_creases(parts_[c].mesh, features, keep);
  }
  // A closed mesh has about 3 edges per vertex (Euler).
  rep_.crease_edge_share = base_vertices > 0.0 ? followed / (3.0 * base_vertices) : 0.0;
  if (options_.creases == CreaseMode::kAuto && rep_.crease_edge_share < kAutoCreaseEdgeShare)
    creases_.assign(parts_.size(), BaseMeshCreases{});
}

std::vector<int> Remesher::oversampling_steps(int levels, int asked) const {
  std::vector<int> steps(parts_.size());
  for (size_t c = 0; c < parts_.size(); ++c)
    steps[c] = asked >= 0 ? asked : auto_steps(parts_[c].mesh, share_[c], levels);
  return steps;
}

uint64_t Remesher::oversampled_vertices(const std::vector<int>& steps) const {
  uint64_t total = 0;
  for (size_t c = 0; c < parts_.size(); ++c)
    total += subdivided_vertices(parts_[c].mesh.positions.size(), parts_[c].mesh.triangles.size(), steps[c]);
  return total;
}

Status Remesher::check_memory(const std::vector<int>& steps) const {
  const uint64_t limit = options_.memory_limit > 0 ? options_.memory_limit : available_memory();
  if (limit == 0) return ok_status();  // not known here: no check
  const uint64_t vertices = oversampled_vertices(steps);
  const uint64_t need = remesh_memory_estimate(vertices);
  if (need <= limit) return ok_status();
  std::string message = "remesh: " + std::to_string(options_.levels) + " levels over " + std::to_string(base_total_) +
                        " base vertices need the input oversampled to about " + std::to_string(vertices) +
                        " vertices, about " + memory_text(need) + " of memory, and " + memory_text(limit) +
                        " is available: ask for";
  // What would fit instead, each estimated the same way.
  auto need_for = [this](int levels, int asked) {
    return memory_text(remesh_memory_estimate(oversampled_vertices(oversampling_steps(levels, asked))));
  };
  if (options_.levels > 0) {
    const int fewer = options_.levels - 1;
    message += " fewer levels (--levels " + std::to_string(fewer) + ": about " + need_for(fewer, options_.oversample) +
               ") or";
  }
  message += " less oversampling (--oversample 0: about " + need_for(options_.levels, 0) + ")";
  return invalid_argument(message);
}

void Remesher::raise_default_base() {
  if (options_.base_vertices != 0) return;
  // The default base size was planned on the oversampling budget; a small
  // input that got all three steps may hold more than planned: as many base
  // vertices as kSupportedRatio oversampled vertices per finest vertex
  // allow, still at most one per 24 input vertices. The quality swings by a
  // few dB with the base size; 6.5 is where the raise helps without starving
  // the cells.
  const double supported = std::min(static_cast<double>(mesh_.positions.size()) / 24.0,
                                    static_cast<double>(rep_.oversampled_vertices) /
                                        (kSupportedRatio * std::pow(4.0, options_.levels)));
  const size_t raised = std::min<size_t>(static_cast<size_t>(std::llround(supported)), kMaxDefaultBase);
  if (raised <= base_total_) return;
  for (size_t c = 0; c < parts_.size(); ++c)
    share_[c] = std::min(parts_[c].mesh.positions.size(),
                         static_cast<size_t>(std::llround(static_cast<double>(share_[c]) * raised / base_total_)));
  base_total_ = raised;
  RemeshProgress p;
  p.step = RemeshStep::kBaseSizeRaised;
  p.vertices = base_total_;
  progress(p);
}

StatusOr<bool> Remesher::enough_for_levels(bool fit) {
  finest_ = static_cast<double>(base_total_) * std::pow(4.0, options_.levels);
  too_few_for_uniform_ = static_cast<double>(rep_.oversampled_vertices) < kMinUniformRatio * finest_;
  const bool too_few_for_levels = options_.uniform && options_.levels > 0 && too_few_for_uniform_;
  if (too_few_for_levels && fit) return false;
  if (too_few_for_levels)
    return invalid_argument(
        "remesh: " + std::to_string(options_.levels) + " uniform levels over " + std::to_string(base_total_) +
        " base vertices make about " + std::to_string(static_cast<size_t>(finest_)) + " vertices, but the input has " +
        std::to_string(rep_.oversampled_vertices) + (rep_.oversample_steps > 0 ? " after oversampling" : "") +
        "; the Voronoi cells need at least " + std::to_string(static_cast<int>(kMinUniformRatio)) +
        " input vertices per output vertex: oversample more (--oversample, up to 3), or ask for fewer levels or fewer "
        "base vertices (--base-vertices)");
  if (base_total_ > rep_.oversampled_vertices)
    return invalid_argument("remesh: " + std::to_string(base_total_) + " base vertices asked but the mesh has only " +
                            std::to_string(rep_.oversampled_vertices) + " vertices" +
                            (rep_.oversample_steps > 0 ? " after oversampling" : "") + "; ask for at most " +
                            std::to_string(rep_.oversampled_vertices / 4) + " (--base-vertices) or oversample more");
  return true;
}

StatusOr<SemiRegularMesh> Remesher::with_fewer_levels(RemeshReport* report) const {
  RemeshOptions fewer = options_;
  fewer.levels = options_.levels - 1;
  RemeshProgress p;
  p.step = RemeshStep::kFewerLevels;
  p.levels = options_.levels;
  p.vertices = static_cast<size_t>(kMinUniformRatio * finest_);
  progress(p);
  return remesh(mesh_, fewer, report);
}

StatusOr<VoronoiCells> Remesher::sites_of(size_t c) {
  const TriangleMesh& part = parts_[c].mesh;
  VoronoiCells cells;
  if (share_[c] >= part.positions.size()) {
    for (size_t v = 0; v < part.positions.size(); ++v) {
      cells.sites.push_back(static_cast<int32_t>(v));
      cells.cell_of.push_back(static_cast<int32_t>(v));
    }
    return cells;
  }
  LbgOptions lbg;
  lbg.target_sites = share_[c];
  lbg.min_flatness = kMinCellFlatness;
  LbgReport lbg_report;
  SRCODEC_ASSIGN_OR_RETURN(cells, lbg_sites(part, lbg, &lbg_report));
  for (const auto& round : lbg_report.rounds) rep_.curled_sites += round.curled_splits;
  BoundaryTipOptions tips;
  tips.reach = boundary_tip_reach(part, share_[c]);
  rep_.tip_sites += add_boundary_tip_sites(part, tips, &cells);
  return cells;
}

Status Remesher::build_base() {
  // All components' sites first, then their base meshes: each step says when
  // it is done (on a large input each takes minutes).
  auto t0 = std::chrono::steady_clock::now();
  std::vector<VoronoiCells> cells(parts_.size());
  size_t sites = 0;
  for (size_t c = 0; c < parts_.size(); ++c) {
    SRCODEC_ASSIGN_OR_RETURN(cells[c], sites_of(c));
    sites += cells[c].sites.size();
  }
  const double sites_s = seconds_since(t0);
  rep_.seconds_sites = sites_s;
  RemeshProgress done;
  done.step = RemeshStep::kSites;
  done.vertices = sites;
  done.seconds = sites_s;
  progress(done);

  t0 = std::chrono::steady_clock::now();
  for (size_t c = 0; c < parts_.size(); ++c) {
    const TriangleMesh& part = parts_[c].mesh;
    BaseMeshReport base_report;
    auto built = build_base_mesh(part, cells[c].sites, cells[c].cell_of, &base_report, creases_[c]);
    if (!built.ok()) return built.status().with_context("component " + std::to_string(c));
    cells[c] = VoronoiCells{};  // its memory back before the next component's collapses
    creases_[c] = BaseMeshCreases{};
    rep_.promoted_vertices += base_report.promoted_vertices;
    rep_.crease_vertices_kept += base_report.crease_vertices_kept;
    const int32_t base_offset = static_cast<int32_t>(base_.mesh.positions.size());
    for (const auto& [a, b] : built->crease_edges) base_.crease_edges.push_back({a + base_offset, b + base_offset});

    const int32_t input_offset = static_cast<int32_t>(input_.positions.size());
    const int32_t face_offset = static_cast<int32_t>(base_.mesh.triangles.size());
    append_mesh(input_, part);
    parts_[c].mesh = TriangleMesh{};  // input_ holds it now; nothing after the base needs the parts
    append_mesh(base_.mesh, built->mesh);
    for (int32_t v : built->input_vertex) base_.input_vertex.push_back(v + input_offset);
    for (const auto& [a, b] : built->input_creases.edges)
      base_.input_creases.edges.push_back({a + input_offset, b + input_offset});
    for (int32_t v : built->input_creases.fixed) base_.input_creases.fixed.push_back(v + input_offset);
    for (ParamPoint p : built->param) {
      p.face += face_offset;
      base_.param.push_back(p);
    }
  }
  const double base_s = seconds_since(t0);
  rep_.seconds_base = base_s;
  rep_.base_vertices = base_.mesh.positions.size();
  rep_.base_crease_edges = base_.crease_edges.size();
  RemeshProgress p;
  p.step = RemeshStep::kBaseMesh;
  p.triangles = base_.mesh.triangles.size();
  p.seconds = base_s;
  progress(p);
  return ok_status();
}

Status Remesher::refine_levels() {
  const auto start = std::chrono::steady_clock::now();
  RefineOptions refine_options;
  refine_options.levels = options_.levels;
  refine_options.threshold = options_.threshold;
  refine_options.uniform = options_.uniform;
  // Eq. 5 judged on a uniform refinement where the input supports one: each
  // adaptive level relaxed on its own relaxes into worse tangles at thin
  // parts, so the paper's order measures lower for as many triangles.
  refine_options.threshold_after_uniform = !options_.uniform && options_.levels > 0 && !too_few_for_uniform_;
  rep_.threshold_after_uniform = refine_options.threshold_after_uniform;
  if (!options_.uniform && options_.levels > 0 && too_few_for_uniform_) {
    RemeshProgress p;
    p.step = RemeshStep::kThresholdLevelByLevel;
    p.levels = options_.levels;
    progress(p);
  }
  if (options_.tolerance_db > 0.0)
    refine_options.tolerance = bounding_box_diagonal(mesh_.positions) * std::pow(10.0, -options_.tolerance_db / 20.0);
  refine_options.max_lloyd_iterations = options_.max_lloyd_iterations;
  refine_options.progress = options_.progress;
  SRCODEC_ASSIGN_OR_RETURN(refined_, refine(input_, base_, refine_options, &rep_.levels));
  rep_.seconds_refine = seconds_since(start);
  positions_ = std::move(refined_.positions);
  for (size_t b = 0; b < base_.mesh.positions.size(); ++b) base_.mesh.positions[b] = positions_[b];  // Lloyd moved them
  return ok_status();
}

void Remesher::fit() {
  const int32_t levels = static_cast<int32_t>(rep_.levels.size());
  if (!options_.fit_surface || levels == 0) return;
  const LevelsToMove moving =
      levels_to_move(refined_.hierarchy, levels, base_.mesh.positions.size(), positions_.size(), base_.crease_edges);
  rep_.fit = fit_to_surface(mesh_, input_, moving.triangles, moving.fixed, &positions_);
  RemeshProgress p;
  p.step = RemeshStep::kFit;
  p.seconds = rep_.fit.seconds;
  progress(p);
}

// The untangling (last; with --max-loss also before the coarsening, so
// that its loss is judged against the untangled full refinement).
void Remesher::untangle_out(SemiRegularMesh* m, const UntangleOptions& untangle_options) {
  const LevelsToMove tangled =
      levels_to_move(m->hierarchy, m->levels, m->base.positions.size(), m->positions.size(), m->crease_edges);
  const auto set_up = std::chrono::steady_clock::now();
  UntangleReport r = untangle(untangle_data(), tangled.triangles, tangled.fixed, &m->positions, untangle_options);
  r.seconds = seconds_since(set_up);  // with the input's set-up, the first time
  if (rep_.untangle.rounds == 0) rep_.untangle.before = r.before;
  rep_.untangle.after = r.after;
  rep_.untangle.moved += r.moved;
  rep_.untangle.joint_moved += r.joint_moved;
  rep_.untangle.rounds += r.rounds;
  rep_.untangle.seconds += r.seconds;
  RemeshProgress p;
  p.step = RemeshStep::kUntangle;
  p.untangle = &r;
  p.wide = untangle_options.wide_candidates > 0;
  p.seconds = r.seconds;
  progress(p);
}

Status Remesher::coarsen(SemiRegularMesh* out, int32_t levels) {
  CoarseningOptions coarsening;
  coarsening.max_loss_db = options_.max_loss_db;
  coarsening.refit = options_.fit_surface;  // --no-fit-surface keeps the sites where they are
  coarsening.deepen_fraction = options_.deepen_fraction;
  SRCODEC_ASSIGN_OR_RETURN(*out, coarsen_by_measured_error(mesh_, input_, *out, coarsening, &rep_.coarsening));
  // The level reports: the last one's splits are those kept (fewer
  // levels when none is).
  rep_.levels.resize(static_cast<size_t>(out->levels));
  for (size_t l = 0; l < rep_.levels.size(); ++l) rep_.levels[l].level = static_cast<int>(l) + 1;
  if (out->levels > levels) {  // deepened: the triangles chosen, and of both last levels, those split in the end
    auto split_at = [&](int32_t level) {
      size_t n = 0;
      for (const TriangleHierarchy::Node& node : out->hierarchy.nodes())
        n += node.level == level && node.first_child >= 0;
      return n;
    };
    RefineLevelReport& asked = rep_.levels[static_cast<size_t>(levels) - 1];
    const size_t kept = split_at(levels - 1);
    asked.within_tolerance = asked.split > kept ? asked.split - kept : 0;
    asked.split = kept;
    rep_.levels.back().selected = rep_.coarsening.deepened;
    rep_.levels.back().split = split_at(levels);
  }
  if (out->levels == levels) {
    RefineLevelReport& last = rep_.levels.back();
    last.within_tolerance = rep_.coarsening.undone;
    last.split = rep_.coarsening.candidates - rep_.coarsening.undone;
  }
  RemeshProgress p;
  p.step = RemeshStep::kMeasuredCoarsening;
  p.level = levels;
  p.seconds = rep_.coarsening.seconds;
  progress(p);
  return ok_status();
}

// Where triangles stay tangled: splits of the level above the finest
// undone around them (remesh/unsplit_tangles.h) and the untangling run
// again. First around the finest level's tangled triangles; then also at
// the corners of the coarser levels' (a corner with no finest triangles
// around it moves as its own levels ask). A pass is kept when it leaves
// fewer tangled triangles, all levels counted; up to 4 passes of each
// kind. The corners left whole are not fitted to the input again (as the
// measured coarsening does): that cost time and PSNR.
Status Remesher::unsplit(SemiRegularMesh* out) {
  for (int kind = 0; kind < 2; ++kind)
    for (int pass = 0; pass < 4 && rep_.untangle.after.total() > 0; ++pass) {
      UnsplitOptions unsplit;
      unsplit.coarser = kind == 1;
      UnsplitReport u;
      SRCODEC_ASSIGN_OR_RETURN(SemiRegularMesh next, unsplit_tangles(untangle_data().side_at(), *out, unsplit, &u));
      rep_.unsplit.seconds += u.seconds;
      if (u.stars == 0) break;
      const UntangleReport untangled = rep_.untangle;
      untangle_out(&next, {});
      const bool kept = rep_.untangle.after.total() < untangled.after.total();
      RemeshProgress p;
      p.step = RemeshStep::kUnsplit;
      p.unsplit = &u;
      p.coarser = unsplit.coarser;
      p.level = out->levels - 1;
      p.tangled_before = untangled.after.total();
      p.tangled_after = rep_.untangle.after.total();
      p.kept = kept;
      p.seconds = u.seconds;
      progress(p);
      if (!kept) {
        rep_.untangle = untangled;
        break;
      }
      *out = std::move(next);
      ++rep_.unsplit.passes;
      rep_.unsplit.stars += u.stars;
      rep_.unsplit.undone += u.undone;
      if (static_cast<size_t>(out->levels) == rep_.levels.size()) {
        RefineLevelReport& last = rep_.levels.back();
        last.split -= std::min(last.split, u.undone);
      }
    }
  return ok_status();
}

// The levels' triangles, for the sliver relaxation and for the places of
// the tangles left; it moves vertices only, so both see the same levels.
void Remesher::relax_and_place(SemiRegularMesh* out) {
  const bool relaxing = options_.relax_slivers && options_.fit_surface && out->levels > 0;
  const bool placing = rep_.untangle.rounds > 0 && rep_.untangle.after.total() > 0;
  const LevelsToMove final_levels =
      relaxing || placing
          ? levels_to_move(out->hierarchy, out->levels, out->base.positions.size(), out->positions.size(),
                           out->crease_edges)
          : LevelsToMove{};
  // No triangle of any level folds or pleats more or less (relax_slivers
  // moves no vertex of a tangled triangle and refuses moves that tangle
  // one), so the untangling's counts stay the output's.
  if (relaxing) {
    rep_.slivers = relax_slivers(untangle_data().side_at(), final_levels.triangles[static_cast<size_t>(out->levels)],
                                 final_levels.triangles[static_cast<size_t>(out->levels) - 1], final_levels.fixed,
                                 &out->positions);
    RemeshProgress p;
    p.step = RemeshStep::kSlivers;
    p.poor_quality = SliverRelaxOptions{}.poor_quality;
    p.seconds = rep_.slivers.seconds;
    progress(p);
  }
  if (placing)
    rep_.tangled_places = tangled_places(untangle_data(), final_levels.triangles, out->positions,
                                         kTangledPlaceReach * bounding_box_diagonal(mesh_.positions));
}

StatusOr<SemiRegularMesh> Remesher::run(RemeshReport* report, bool fit_levels) {
  SRCODEC_RETURN_IF_ERROR(split_and_oversample());
  raise_default_base();
  SRCODEC_ASSIGN_OR_RETURN(const bool enough, enough_for_levels(fit_levels));
  if (!enough) return with_fewer_levels(report);
  SRCODEC_RETURN_IF_ERROR(build_base());
  SRCODEC_RETURN_IF_ERROR(refine_levels());
  fit();
  const int32_t levels = static_cast<int32_t>(rep_.levels.size());
  SemiRegularMesh out{std::move(base_.mesh), std::move(refined_.hierarchy), std::move(positions_), levels,
                      std::move(base_.crease_edges)};
  const bool untangling = options_.fit_surface && options_.untangle && levels > 0;
  if (untangling && options_.max_loss_db > 0.0) untangle_out(&out, {});
  if (options_.max_loss_db > 0.0 && levels > 0) SRCODEC_RETURN_IF_ERROR(coarsen(&out, levels));
  if (untangling && out.levels > 0) untangle_out(&out, {});
  if (options_.unsplits() && out.levels > 0) SRCODEC_RETURN_IF_ERROR(unsplit(&out));
  // Last, where triangles stay tangled: one more untangling that also tries,
  // for each free vertex, the 128 input vertices nearest it and as many
  // nearest its neighbours' centroid (UntangleOptions::wide_candidates): an
  // input vertex carries its own side, which can put a corner back on its
  // neighbours' sheet. Only here, not in every pass: everywhere it moves far
  // more vertices and costs PSNR.
  if (untangling && out.levels > 0 && rep_.untangle.after.total() > 0) {
    UntangleOptions wide;
    wide.wide_candidates = 128;
    untangle_out(&out, wide);
  }
  relax_and_place(&out);
  return out;
}

}  // namespace

StatusOr<SemiRegularMesh> remesh(const TriangleMesh& mesh, const RemeshOptions& options, RemeshReport* report) {
  RemeshReport local;
  RemeshReport& rep = report ? *report : local;
  rep = RemeshReport{};
  SRCODEC_RETURN_IF_ERROR(check_options(options));
  if (mesh.triangles.empty()) return invalid_mesh("remesh: the mesh has no triangles");
  Remesher remesher(mesh, options, rep);
  const bool fit = options.fit_levels && options.base_vertices == 0;
  if (fit && mesh.positions.size() < kMinDefaultBase) return remesher.whole_input_as_base(report);
  return remesher.run(report, fit);
}

}  // namespace srcodec
