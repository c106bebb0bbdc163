// <srcodec/encoder.h>: encode() checks the public options, cleans the mesh
// as read_mesh does and runs the encoder's steps (codec/encode_mesh.h).
#include <srcodec/encoder.h>

#include <cmath>
#include <string>

#include "codec/encode_mesh.h"
#include "format/mesh_convert.h"
#include "format/mesh_files/mesh_clean.h"
#include "format/srm/srm_file.h"

namespace srcodec {
namespace {

// `value` within [lo, hi] and finite, else a message naming the option.
Status check_range(const char* name, double value, double lo, double hi) {
  if (std::isfinite(value) && value >= lo && value <= hi) return ok_status();
  return invalid_argument(std::string("EncodeOptions::") + name + " " + number_text(value) + ": use " +
                          number_text(lo) + " .. " + number_text(hi));
}

Status check_rate(const Rate& rate) {
  switch (rate.kind) {
    case Rate::Kind::kKnee:
      return ok_status();
    case Rate::Kind::kBytes:
      if (rate.value >= 1 && rate.value <= 9.0e15 && std::floor(rate.value) == rate.value) return ok_status();
      return invalid_argument("Rate::bytes " + number_text(rate.value) + ": use a whole number of bytes, at least 1");
    case Rate::Kind::kBitsPerVertex:
      return check_range("rate (bits per vertex)", rate.value, 1e-6, 1e6);
    case Rate::Kind::kPsnr:
      return check_range("rate (PSNR in dB)", rate.value, 1e-6, 1e3);
  }
  return invalid_argument("EncodeOptions::rate: unknown kind " + std::to_string(static_cast<int>(rate.kind)));
}

Status check_options(const EncodeOptions& o) {
  if (o.levels < -1 || o.levels > kSrmMaxLevels)
    return invalid_argument("EncodeOptions::levels " + std::to_string(o.levels) +
                            ": use -1 (chosen from the input) or 0 .. " + std::to_string(kSrmMaxLevels));
  switch (o.adaptivity) {
    case Adaptivity::kUniform:
      break;
    case Adaptivity::kVertexCount:
      SRCODEC_RETURN_IF_ERROR(check_range("threshold", o.threshold, 0.0, 1e12));
      break;
    case Adaptivity::kMeasuredError:
      SRCODEC_RETURN_IF_ERROR(check_range("max_loss_db", o.max_loss_db, 0.01, 60.0));
      SRCODEC_RETURN_IF_ERROR(check_range("deepen_fraction", o.deepen_fraction, 0.0, 1.0));
      break;
    default:
      return invalid_argument("EncodeOptions::adaptivity: unknown value " +
                              std::to_string(static_cast<int>(o.adaptivity)));
  }
  if (o.creases != Creases::kAuto && o.creases != Creases::kKeep && o.creases != Creases::kOff)
    return invalid_argument("EncodeOptions::creases: unknown value " + std::to_string(static_cast<int>(o.creases)));
  SRCODEC_RETURN_IF_ERROR(check_rate(o.rate));
  SRCODEC_RETURN_IF_ERROR(check_range("tangential_factor", o.tangential_factor, 0.25, 64.0));
  SRCODEC_RETURN_IF_ERROR(check_range("base_bits", o.base_bits, 4, 24));
  return check_range("raw_planes", o.raw_planes, 0, kSrmMaxPlane + 1);
}

MeshEncodeOptions to_mesh_encode_options(const EncodeOptions& o) {
  MeshEncodeOptions m;
  RemeshOptions& r = m.remesh;
  r.levels = o.levels < 0 ? RemeshOptions{}.levels : o.levels;
  r.fit_levels = o.levels < 0;
  r.base_vertices = o.base_vertices;
  r.uniform = o.adaptivity != Adaptivity::kVertexCount;
  r.threshold = o.adaptivity == Adaptivity::kVertexCount ? o.threshold : 0.0;
  r.max_loss_db = o.adaptivity == Adaptivity::kMeasuredError ? o.max_loss_db : 0.0;
  r.deepen_fraction = o.adaptivity == Adaptivity::kMeasuredError ? o.deepen_fraction : 0.0;
  r.creases = o.creases == Creases::kKeep  ? CreaseMode::kKeep
              : o.creases == Creases::kOff ? CreaseMode::kIgnore
                                           : CreaseMode::kAuto;
  m.coding.tangential_factor = o.tangential_factor;
  m.coding.base_bits = o.base_bits;
  m.coding.raw_planes = o.raw_planes;
  m.rate = o.rate;
  m.progress = o.progress;
  return m;
}

// The mesh as the stages take it: checked, then cleaned as read_mesh cleans.
StatusOr<TriangleMesh> cleaned(const Mesh& mesh) {
  SRCODEC_ASSIGN_OR_RETURN(const TriangleMesh checked, from_public_mesh(mesh, "the mesh to encode"));
  TriangleMesh out = clean_mesh(to_polygon_mesh(checked));
  if (out.triangles.empty())
    return invalid_mesh("the mesh to encode has no triangle of positive area (after welding coincident vertices "
                        "and dropping degenerate faces)");
  return out;
}

}  // namespace

StatusOr<std::vector<uint8_t>> encode(const Mesh& mesh, const EncodeOptions& options, EncodeReport* report) {
  SRCODEC_RETURN_IF_ERROR(check_options(options));
  SRCODEC_ASSIGN_OR_RETURN(const TriangleMesh input, cleaned(mesh));
  SRCODEC_ASSIGN_OR_RETURN(MeshEncodeResult result, encode_mesh(input, to_mesh_encode_options(options)));
  if (report != nullptr) {
    report->levels = result.header.levels;
    report->base_vertices = result.header.base_vertices;
    report->crease_edges = result.crease_edges;
    report->bytes = result.file.size();
    report->full_stream_bytes = result.full_stream_bytes;
    report->minimum_bytes = result.minimum_bytes;
    report->psnr = result.psnr;
    report->seconds_remesh = result.seconds_remesh;
    report->seconds_coding = result.seconds_coding;
    report->seconds_rate = result.seconds_rate;
  }
  return std::move(result.file);
}

}  // namespace srcodec
