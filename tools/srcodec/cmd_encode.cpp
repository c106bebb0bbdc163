// `srcodec encode MESH -o OUT.srm`: remesh, transform, code, and keep as much
// of the embedded stream as the rate option asks (--bytes, --bpv, --psnr).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "codec/rate_control.h"
#include "codec/srm_codec.h"
#include "format/file_io.h"
#include "format/mesh_files/mesh_io.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"
#include "tools/srcodec/remesh_flags.h"

namespace srcodec {
namespace {

struct EncodeCliOptions {
  std::string input, output;
  RemeshFlags remesh;
  double bpv = -1.0, psnr = -1.0;
  uint64_t bytes = 0;
  double tangential_factor = 4.0;
  int base_bits = 10;
  int raw_planes = SrmEncodeOptions{}.raw_planes;
  size_t samples = 200000;
  bool json = false, quiet = false;
};

Status run_encode(const EncodeCliOptions& o) {
  SRCODEC_ASSIGN_OR_RETURN(RemeshOptions remesh_options, to_remesh_options(o.remesh));
  SRCODEC_RETURN_IF_ERROR(check_output_path(o.output));
  const auto say = [&](const std::string& line) {
    if (!o.quiet) std::cerr << "encode: " << line << std::endl;
  };
  if (!o.quiet) remesh_options.progress = [](const std::string& line) { std::cerr << "remesh: " << line << std::endl; };
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh input, read_triangle_mesh(o.input));
  const auto start = std::chrono::steady_clock::now();
  RemeshReport remesh_report;
  SRCODEC_ASSIGN_OR_RETURN(SemiRegularMesh srm, remesh(input, remesh_options, &remesh_report));
  const double remesh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  SrmEncodeOptions encode_options;
  encode_options.tangential_factor = o.tangential_factor;
  encode_options.base_bits = o.base_bits;
  encode_options.raw_planes = o.raw_planes;
  const auto coding_start = std::chrono::steady_clock::now();
  SRCODEC_ASSIGN_OR_RETURN(EncodedSrm encoded, encode_srm(srm, input, encode_options));
  const double coding_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - coding_start).count();
  const uint64_t full = encoded.bytes.size();
  const StreamCutter cutter(input, encoded.bytes);
  // Header, base mesh and flags: the least a file can hold.
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> smallest, cutter.cut(0));
  const uint64_t minimum = smallest.size();

  uint64_t segment_bytes = cutter.segment_bytes();
  std::string rate;
  if (o.bytes > 0 || o.bpv > 0) {
    const uint64_t budget =
        o.bytes > 0 ? o.bytes : static_cast<uint64_t>(std::floor(o.bpv * input.positions.size() / 8.0));
    rate = o.bytes > 0 ? "--bytes " + std::to_string(o.bytes) : "--bpv " + std::to_string(o.bpv);
    if (budget < minimum)
      return invalid_argument(rate + " allows " + std::to_string(budget) + " bytes, fewer than the " +
                              std::to_string(minimum) + " that the header, base mesh and refinement flags take "
                              "(try fewer --base-vertices or --levels)");
    SRCODEC_ASSIGN_OR_RETURN(segment_bytes, cutter.segment_bytes_within(budget));
  } else if (o.psnr > 0) {
    const double target = o.psnr;
    SRCODEC_ASSIGN_OR_RETURN(double best, whole_stream_psnr(cutter));
    rate = "--psnr " + std::to_string(target);
    if (best < target)
      return invalid_argument("--psnr " + std::to_string(target) + " is out of reach: the whole stream gives " +
                              std::to_string(best) + " dB, limited by the remesh (try more --levels or " +
                              "--base-vertices)");
    say("searching for the shortest stream that reaches " + std::to_string(target) + " dB");
    SRCODEC_ASSIGN_OR_RETURN(segment_bytes, segment_bytes_for_psnr(cutter, target));
  } else {
    char per_bpv[32];
    std::snprintf(per_bpv, sizeof per_bpv, "%g", kKneeDbPerBpv);
    say(std::string("no rate option given: measuring cuts of the stream up to its knee, where one more bit per input "
                    "vertex gains less than ") + per_bpv + " dB (use --bpv, --bytes or --psnr to choose)");
    SRCODEC_ASSIGN_OR_RETURN(Knee knee, knee_of_stream(cutter, input.positions.size()));
    segment_bytes = knee.segment_bytes;
    rate = knee.whole_stream ? std::string("the whole stream (no knee before it)")
                             : std::string("the knee at ") + per_bpv + " dB/bpv";
    char line[160];
    const char* whole = !knee.whole_stream          ? ""
                        : std::isfinite(knee.psnr) ? ", the whole stream"
                                                   : ": the whole stream reproduces the input exactly";
    std::snprintf(line, sizeof line, "%d cut%s measured: keeping %llu of %llu bytes, %.2f dB%s", knee.cuts,
                  knee.cuts == 1 ? "" : "s", static_cast<unsigned long long>(knee.file_bytes),
                  static_cast<unsigned long long>(full), knee.psnr, whole);
    say(line);
  }
  SRCODEC_ASSIGN_OR_RETURN(std::vector<uint8_t> file, cutter.cut(segment_bytes));
  const uint64_t keep = file.size();
  SRCODEC_ASSIGN_OR_RETURN(double psnr, cutter.psnr(segment_bytes, o.samples));
  SRCODEC_RETURN_IF_ERROR(write_file_atomically(o.output, std::string(file.begin(), file.end())));
  const double bpv = 8.0 * keep / input.positions.size();
  if (o.json) {
    JsonWriter j;
    j.field("input", o.input)
        .field("output", o.output)
        .field("input_vertices", input.positions.size())
        .field("levels", encoded.header.levels)
        .field("base_vertices", static_cast<size_t>(encoded.header.base_vertices))
        .field("rate", rate)
        .field("bytes", static_cast<size_t>(keep))
        .field("full_stream_bytes", static_cast<size_t>(full))
        .field("minimum_bytes", static_cast<size_t>(minimum))
        .field("bpv", bpv)
        .field("psnr", psnr)
        .field("unsplit_tangles", remesh_options.unsplits())
        .field("unsplit_splits", remesh_report.unsplit.undone)
        .field("remesh_seconds", remesh_seconds)
        .field("coding_seconds", coding_seconds);
    std::cout << j.str() << "\n";
  } else {
    std::printf("%s: %zu vertices -> %s: %llu bytes (%.3f bpv), %.2f dB PSNR, %d levels over %llu base vertices\n",
                o.input.c_str(), input.positions.size(), o.output.c_str(), static_cast<unsigned long long>(keep), bpv,
                psnr, encoded.header.levels, static_cast<unsigned long long>(encoded.header.base_vertices));
    std::printf("  rate %s; full stream %llu bytes; remesh %.2f s, coding %.2f s\n", rate.c_str(),
                static_cast<unsigned long long>(full), remesh_seconds, coding_seconds);
  }
  return ok_status();
}

}  // namespace

Command add_encode_command(CommandLine& cli) {
  auto o = std::make_shared<EncodeCliOptions>();
  Subcommand& cmd = cli.add_command(
      "encode",
      "Remesh and compress a mesh into a progressive .srm file; with no rate option it keeps the knee of the "
      "stream's rate-distortion curve (README: The default rate)");
  cmd.positional("mesh", o->input, "Input mesh (OBJ, PLY, OFF, STL)");
  cmd.option("-o,--output", o->output, "The .srm file to write").required();
  add_remesh_flags(cmd, o->remesh, /*for_coding=*/true);
  auto& bpv = cmd.option("--bpv", o->bpv, "Rate: bits per input vertex").finite().positive();
  auto& bytes = cmd.option("--bytes", o->bytes, "Rate: file size in bytes").positive();
  auto& psnr = cmd.option("--psnr", o->psnr, "Rate: the smallest file reaching this PSNR (dB) against the input")
                   .finite()
                   .positive();
  bpv.excludes(bytes).excludes(psnr);
  bytes.excludes(psnr);
  cmd.option("--tangential-factor", o->tangential_factor,
             "Quantizer step of tangential detail components relative to normal ones")
      .finite()
      .range(0.25, 64.0)
      .show_default();
  cmd.option("--base-bits", o->base_bits, "Bits per coordinate of the base mesh grid").range(4, 24).show_default();
  cmd.option("--raw-planes", o->raw_planes,
             "The symbols of this many lowest bit planes are stored as raw bits (faster decoding, "
             "slightly larger); 0 writes .srm version 1")
      .range(0, kSrmMaxPlane + 1)
      .show_default();
  cmd.option("--samples", o->samples, "Samples per surface for the PSNR figures")
      .range(size_t{1000}, size_t{100000000})
      .show_default();
  cmd.flag("--json", o->json, "Print one JSON object");
  cmd.flag("-q,--quiet", o->quiet, "No progress lines on stderr");
  return {&cmd, [o] { return run_encode(*o); }};
}

}  // namespace srcodec
