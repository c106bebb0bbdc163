// `srcodec encode MESH -o OUT.srm`: remesh, transform, code, and keep as much
// of the embedded stream as the rate option asks (--bytes, --bpv, --psnr).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "codec/encode_mesh.h"
#include "format/file_io.h"
#include "tools/srcodec/commands.h"
#include "tools/srcodec/json_writer.h"
#include "tools/srcodec/remesh_flags.h"
#include "tools/srcodec/remesh_progress.h"

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

Rate rate_of(const EncodeCliOptions& o) {
  if (o.bytes > 0) return Rate::bytes(o.bytes);
  if (o.bpv > 0) return Rate::bits_per_vertex(o.bpv);
  if (o.psnr > 0) return Rate::psnr(o.psnr);
  return Rate::knee();
}

// What the rate step is about to do, said once the stream is coded.
std::string rate_search_line(const Rate& rate) {
  char line[200];
  if (rate.kind == Rate::Kind::kPsnr) {
    std::snprintf(line, sizeof line, "searching for the shortest stream that reaches %g dB", rate.value);
  } else if (rate.kind == Rate::Kind::kKnee) {
    std::snprintf(line, sizeof line,
                  "no rate option given: measuring cuts of the stream up to its knee, where one more bit per input "
                  "vertex gains less than %g dB (use --bpv, --bytes or --psnr to choose)",
                  kKneeDbPerBpv);
  } else {
    return "";
  }
  return line;
}

// The rate kept, in words, and with the knee where its search stopped.
std::string rate_text(const EncodeCliOptions& o, const Knee& knee) {
  char text[64];
  if (o.bytes > 0) return "--bytes " + std::to_string(o.bytes);
  if (o.bpv > 0) return "--bpv " + std::to_string(o.bpv);
  if (o.psnr > 0) return "--psnr " + std::to_string(o.psnr);
  if (knee.whole_stream) return "the whole stream (no knee before it)";
  std::snprintf(text, sizeof text, "the knee at %g dB/bpv", kKneeDbPerBpv);
  return text;
}

std::string knee_line(const MeshEncodeResult& r) {
  const Knee& knee = r.knee;
  const char* whole = !knee.whole_stream          ? ""
                      : std::isfinite(knee.psnr) ? ", the whole stream"
                                                 : ": the whole stream reproduces the input exactly";
  char line[200];
  std::snprintf(line, sizeof line, "%d cut%s estimated, %d measured: keeping %llu of %llu bytes, %.2f dB%s",
                knee.estimated_cuts, knee.estimated_cuts == 1 ? "" : "s", knee.cuts,
                static_cast<unsigned long long>(knee.file_bytes),
                static_cast<unsigned long long>(r.full_stream_bytes), knee.psnr, whole);
  return line;
}

void print_result(const EncodeCliOptions& o, const MeshEncodeOptions& options, const TriangleMesh& input,
                  const MeshEncodeResult& r) {
  const uint64_t keep = r.file.size();
  const double bpv = 8.0 * keep / input.positions.size();
  const std::string rate = rate_text(o, r.knee);
  if (o.json) {
    JsonWriter j;
    j.field("input", o.input)
        .field("output", o.output)
        .field("input_vertices", input.positions.size())
        .field("levels", r.header.levels)
        .field("base_vertices", static_cast<size_t>(r.header.base_vertices))
        .field("crease_edges", r.crease_edges)
        .field("rate", rate)
        .field("bytes", static_cast<size_t>(keep))
        .field("full_stream_bytes", static_cast<size_t>(r.full_stream_bytes))
        .field("minimum_bytes", static_cast<size_t>(r.minimum_bytes))
        .field("bpv", bpv)
        .field("psnr", r.psnr)
        .field("unsplit_tangles", options.remesh.unsplits())
        .field("unsplit_splits", r.remesh.unsplit.undone)
        .field("remesh_seconds", r.seconds_remesh)
        .field("coding_seconds", r.seconds_coding)
        .field("rate_seconds", r.seconds_rate);
    std::cout << j.str() << "\n";
    return;
  }
  std::printf("%s: %zu vertices -> %s: %llu bytes (%.3f bpv), %.2f dB PSNR, %d levels over %llu base vertices\n",
              o.input.c_str(), input.positions.size(), o.output.c_str(), static_cast<unsigned long long>(keep), bpv,
              r.psnr, r.header.levels, static_cast<unsigned long long>(r.header.base_vertices));
  std::printf("  rate %s; full stream %llu bytes; remesh %.2f s, coding %.2f s, rate %.2f s\n", rate.c_str(),
              static_cast<unsigned long long>(r.full_stream_bytes), r.seconds_remesh, r.seconds_coding,
              r.seconds_rate);
}

Status run_encode(const EncodeCliOptions& o) {
  MeshEncodeOptions options;
  SRCODEC_ASSIGN_OR_RETURN(options.remesh, to_remesh_options(o.remesh));
  SRCODEC_RETURN_IF_ERROR(check_output_path(o.output));
  options.coding.tangential_factor = o.tangential_factor;
  options.coding.base_bits = o.base_bits;
  options.coding.raw_planes = o.raw_planes;
  options.rate = rate_of(o);
  options.samples = o.samples;
  if (!o.quiet) {
    options.remesh.progress =
        remesh_progress_lines([](const std::string& line) { std::cerr << "remesh: " << line << std::endl; });
    options.progress = [rate = options.rate](const EncodeProgress& p) {
      const std::string line = rate_search_line(rate);
      if (std::string(p.stage) == "code" && !line.empty()) std::cerr << "encode: " << line << std::endl;
    };
  }
  SRCODEC_ASSIGN_OR_RETURN(TriangleMesh input, read_mesh_with_progress(o.input, o.quiet, "encode: "));
  SRCODEC_ASSIGN_OR_RETURN(MeshEncodeResult result, encode_mesh(input, options));
  if (!o.quiet && options.rate.kind == Rate::Kind::kKnee) std::cerr << "encode: " << knee_line(result) << std::endl;
  SRCODEC_RETURN_IF_ERROR(write_file_atomically(o.output, std::string(result.file.begin(), result.file.end())));
  print_result(o, options, input, result);
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
  add_remesh_flags(cmd, o->remesh);
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
