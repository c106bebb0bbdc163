// Decoder and encoder speed, srcodec against Draco in the same process
// (issue: encode/decode). For each mesh: remesh once (not timed here), then
//  - srcodec encode without the remeshing: encode_srm, median of runs;
//  - srcodec decode to the finest level: parse + decode_srm of the whole
//    stream, of a file holding a tenth of its coefficient bytes and of the
//    file `srcodec encode` writes with no rate option (the knee of the
//    stream's rate-distortion curve, codec/rate_control.h), median of
//    runs, in output triangles per second;
//  - Draco decode of the input mesh (cl 10, qp 11 and 14), median of runs, in
//    output triangles per second;
//  - srcodec decode at equal quality to each Draco setting: Draco's decoded
//    PSNR against the input (surface_distance with its defaults, as `srcodec
//    compare` measures), then the shortest cut of the srcodec stream reaching
//    that PSNR, found by `srcodec encode --psnr`'s own rate control
//    (codec/rate_control.h), and its decode timed;
//  - per mesh, each srcodec decode's rate over the faster Draco decode's in
//    this run (the figure to take medians of across runs).
// Usage: codec_speed MESH... [--levels L] [--runs N] [--cache DIR]
// --cache DIR keeps each encoded stream in DIR (named after the mesh and L)
// and reuses it on later runs, skipping the remeshing and the encode timing:
// for iterating on the decoder. The equal-quality cuts and the default file
// are cached there too.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "codec/rate_control.h"
#include "codec/srm_codec.h"
#include "format/mesh_files/mesh_io.h"
#include "remesh/remesher.h"
#include "tools/measure/draco_baseline.h"
#include "tools/measure/surface_distance.h"

namespace {

using namespace srcodec;

template <typename F>
double median_ms(int runs, F&& f) {
  std::vector<double> ms;
  for (int r = 0; r < runs; ++r) {
    const auto start = std::chrono::steady_clock::now();
    f();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

// Median decode time of `bytes` and the triangle count it decodes to.
std::pair<double, size_t> time_decode(const std::vector<uint8_t>& bytes, int runs) {
  size_t triangles = 0;
  const double ms = median_ms(runs, [&] {
    StatusOr<SrmFile> f = parse_srm(bytes.data(), bytes.size());
    StatusOr<DecodedSrm> d = decode_srm(f.value());
    if (!d.ok()) {
      std::fprintf(stderr, "decode failed: %s\n", d.status().message().c_str());
      std::exit(1);
    }
    triangles = d->mesh.triangles.size();
  });
  return {ms, triangles};
}

std::string cache_path(const std::string& dir, const std::string& mesh, int levels, const std::string& what = "") {
  const size_t slash = mesh.find_last_of('/');
  return dir + "/" + (slash == std::string::npos ? mesh : mesh.substr(slash + 1)) + ".L" + std::to_string(levels) +
         what + ".srm";
}

std::vector<uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// The shortest cut of `stream` whose PSNR against `input` reaches `target`,
// as `srcodec encode --psnr target` chooses it; empty (and *best set) when
// the whole stream stays below the target.
StatusOr<std::vector<uint8_t>> cut_for_psnr(const TriangleMesh& input, const std::vector<uint8_t>& stream,
                                            double target, double* best) {
  const StreamCutter cutter(input, stream);
  SRCODEC_ASSIGN_OR_RETURN(*best, whole_stream_psnr(cutter));
  if (*best < target) return std::vector<uint8_t>{};
  SRCODEC_ASSIGN_OR_RETURN(uint64_t segment_bytes, segment_bytes_for_psnr(cutter, target));
  return cutter.cut(segment_bytes);
}

double psnr_of(const TriangleMesh& input, const TriangleMesh& decoded) {
  return cgal_surface_distance(input, decoded).value().psnr;
}

// Remeshes and encodes `input` (median encode time in *encode_ms), or reads
// the stream from the cache (*encode_ms = -1). Empty on failure.
std::vector<uint8_t> encoded_stream(const TriangleMesh& input, const std::string& cached, int levels, int runs,
                                    double* encode_ms) {
  *encode_ms = -1;
  if (!cached.empty()) {
    std::vector<uint8_t> bytes = read_bytes(cached);
    if (!bytes.empty()) return bytes;
  }
  RemeshOptions options;
  options.levels = levels;
  StatusOr<SemiRegularMesh> srm = remesh(input, options);
  if (!srm.ok()) {
    std::fprintf(stderr, "%s\n", srm.status().message().c_str());
    return {};
  }
  EncodedSrm encoded;
  *encode_ms = median_ms(runs, [&] { encoded = encode_srm(srm.value(), input).value(); });
  if (!cached.empty()) write_bytes(cached, encoded.bytes);
  return encoded.bytes;
}

int run(const std::string& path, int levels, int runs, const std::string& cache_dir) {
  StatusOr<TriangleMesh> input = read_triangle_mesh(path);
  if (!input.ok()) {
    std::fprintf(stderr, "%s\n", input.status().message().c_str());
    return 1;
  }
  EncodedSrm encoded;
  double encode_ms = -1;
  encoded.bytes = encoded_stream(input.value(), cache_dir.empty() ? "" : cache_path(cache_dir, path, levels), levels,
                                 runs, &encode_ms);
  if (encoded.bytes.empty()) return 1;
  // A tenth of the stream's segment bytes: a typical rate-controlled file.
  const SrmFile whole = parse_srm(encoded.bytes.data(), encoded.bytes.size()).value();
  uint64_t segment_bytes = 0;
  for (const SrmChunk& c : whole.segments) segment_bytes += c.declared;
  const std::vector<uint8_t> tenth = truncate_srm(encoded.bytes, segment_bytes / 10).value();
  // The file `srcodec encode` writes with no rate option: the knee of the
  // stream's rate-distortion curve (cached with the stream, as ".knee").
  const std::string default_cached = cache_dir.empty() ? "" : cache_path(cache_dir, path, levels, ".knee");
  std::vector<uint8_t> default_file = default_cached.empty() ? std::vector<uint8_t>{} : read_bytes(default_cached);
  if (default_file.empty()) {
    const StreamCutter cutter(input.value(), encoded.bytes);
    StatusOr<Knee> knee = knee_of_stream(cutter, input.value().positions.size());
    StatusOr<std::vector<uint8_t>> cut = knee.ok() ? cutter.cut(knee.value().segment_bytes) : knee.status();
    if (!cut.ok()) {
      std::fprintf(stderr, "%s\n", cut.status().message().c_str());
      return 1;
    }
    default_file = std::move(cut.value());
    if (!default_cached.empty()) write_bytes(default_cached, default_file);
  }
  const auto [full_ms, full_tris] = time_decode(encoded.bytes, runs);
  const auto [tenth_ms, tenth_tris] = time_decode(tenth, runs);
  const auto [default_ms, default_tris] = time_decode(default_file, runs);
  const SrmFile parsed_default = parse_srm(default_file.data(), default_file.size()).value();
  const double default_psnr = psnr_of(input.value(), decode_srm(parsed_default).value().mesh);
  if (encode_ms >= 0)
    std::printf("| %s | srcodec encode (no remesh) | %zu B | %.1f ms | |\n", path.c_str(), encoded.bytes.size(),
                encode_ms);
  std::printf("| %s | srcodec decode, whole stream | %zu B | %.1f ms | %.2f M tri/s |\n", path.c_str(),
              encoded.bytes.size(), full_ms, full_tris / full_ms / 1e3);
  std::printf("| %s | srcodec decode, 1/10 of the stream | %zu B | %.1f ms | %.2f M tri/s |\n", path.c_str(),
              tenth.size(), tenth_ms, tenth_tris / tenth_ms / 1e3);
  std::printf("| %s | srcodec decode, default file (%.2f dB) | %zu B | %.1f ms | %.2f M tri/s |\n", path.c_str(),
              default_psnr, default_file.size(), default_ms, default_tris / default_ms / 1e3);
  double draco_best = 0;  // the faster Draco decode's output triangles per ms
  std::vector<std::pair<int, double>> equal_rates;  // (qp, triangles per ms) at Draco qp's PSNR
  for (int qp : {11, 14}) {
    DracoOptions d;
    d.quantization_bits = qp;
    const DracoRoundTrip trip = draco_round_trip(input.value(), d).value();
    size_t tris = 0;
    const double ms = median_ms(runs, [&] { tris = draco_decode(trip.encoded).value().triangles.size(); });
    draco_best = std::max(draco_best, tris / ms);
    const double draco_psnr = psnr_of(input.value(), trip.decoded);
    std::printf("| %s | Draco decode qp %d (%.2f dB) | %zu B | %.1f ms | %.2f M tri/s |\n", path.c_str(), qp,
                draco_psnr, trip.encoded.size(), ms, tris / ms / 1e3);
    // srcodec at Draco's PSNR: the rate-controlled file `srcodec encode
    // --psnr` would write from this stream (cached with the stream).
    const std::string cached =
        cache_dir.empty() ? "" : cache_path(cache_dir, path, levels, ".draco-qp" + std::to_string(qp));
    std::vector<uint8_t> equal = cached.empty() ? std::vector<uint8_t>{} : read_bytes(cached);
    if (equal.empty()) {
      double best = 0;
      StatusOr<std::vector<uint8_t>> cut = cut_for_psnr(input.value(), encoded.bytes, draco_psnr, &best);
      if (!cut.ok()) {
        std::fprintf(stderr, "%s\n", cut.status().message().c_str());
        return 1;
      }
      if (cut->empty()) {
        std::printf("| %s | srcodec decode at Draco qp %d's PSNR | out of reach: the whole stream gives %.2f dB | | |\n",
                    path.c_str(), qp, best);
        continue;
      }
      equal = std::move(cut.value());
      if (!cached.empty()) write_bytes(cached, equal);
    }
    const auto [equal_ms, equal_tris] = time_decode(equal, runs);
    const SrmFile equal_file = parse_srm(equal.data(), equal.size()).value();
    const double equal_psnr = psnr_of(input.value(), decode_srm(equal_file).value().mesh);
    std::printf("| %s | srcodec decode at Draco qp %d's PSNR (%.2f dB) | %zu B | %.1f ms | %.2f M tri/s |\n",
                path.c_str(), qp, equal_psnr, equal.size(), equal_ms, equal_tris / equal_ms / 1e3);
    equal_rates.push_back({qp, equal_tris / equal_ms});
  }
  std::printf("| %s | over the faster Draco decode | whole %.3fx, tenth %.3fx, default %.3fx", path.c_str(),
              full_tris / full_ms / draco_best, tenth_tris / tenth_ms / draco_best,
              default_tris / default_ms / draco_best);
  for (const auto& [qp, rate] : equal_rates) std::printf(", at qp %d's PSNR %.3fx", qp, rate / draco_best);
  std::printf(" | | |\n");
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int levels = 4, runs = 5;
  std::string cache_dir;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--levels") && i + 1 < argc) {
      levels = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--cache") && i + 1 < argc) {
      cache_dir = argv[++i];
    } else {
      meshes.push_back(argv[i]);
    }
  }
  if (meshes.empty()) {
    std::fprintf(stderr, "usage: codec_speed MESH... [--levels L] [--runs N] [--cache DIR]\n");
    return 2;
  }
  std::printf("| mesh | what | bytes | median time | output triangles per second |\n|---|---|---|---|---|\n");
  for (const auto& m : meshes)
    if (run(m, levels, runs, cache_dir)) return 1;
  return 0;
}
