#include "tools/measure/draco_baseline.h"

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>

#include <chrono>
#include <limits>
#include <memory>

namespace srcodec {
namespace {

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::unique_ptr<draco::Mesh> to_draco(const TriangleMesh& mesh) {
  auto out = std::make_unique<draco::Mesh>();
  const auto n = static_cast<uint32_t>(mesh.positions.size());
  out->set_num_points(n);
  draco::GeometryAttribute position;
  position.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  const int id = out->AddAttribute(position, true, n);
  draco::PointAttribute* attribute = out->attribute(id);
  for (uint32_t i = 0; i < n; ++i) {
    const Eigen::Vector3f p = mesh.positions[i].cast<float>();
    attribute->SetAttributeValue(draco::AttributeValueIndex(i), p.data());
  }
  out->SetNumFaces(mesh.triangles.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f) {
    const auto& t = mesh.triangles[f];
    draco::Mesh::Face face = {draco::PointIndex(static_cast<uint32_t>(t[0])), draco::PointIndex(static_cast<uint32_t>(t[1])),
                              draco::PointIndex(static_cast<uint32_t>(t[2]))};
    out->SetFace(draco::FaceIndex(static_cast<uint32_t>(f)), face);
  }
  return out;
}

}  // namespace

StatusOr<TriangleMesh> draco_decode(const std::string& bytes) {
  draco::DecoderBuffer buffer;
  buffer.Init(bytes.data(), bytes.size());
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
  if (!decoded.ok()) return parse_error("Draco could not decode: " + decoded.status().error_msg_string());
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const draco::PointAttribute* position = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  if (!position) return parse_error("Draco stream has no position attribute");

  TriangleMesh out;
  out.positions.resize(mesh->num_points());
  for (uint32_t i = 0; i < mesh->num_points(); ++i) {
    float p[3];
    if (!position->ConvertValue<float, 3>(position->mapped_index(draco::PointIndex(i)), p))
      return parse_error("Draco position " + std::to_string(i) + " cannot be read as 3 floats");
    out.positions[i] = Eigen::Vector3d(p[0], p[1], p[2]);
  }
  out.triangles.resize(mesh->num_faces());
  for (uint32_t f = 0; f < mesh->num_faces(); ++f) {
    const auto& face = mesh->face(draco::FaceIndex(f));
    for (int k = 0; k < 3; ++k) out.triangles[f][k] = static_cast<int32_t>(face[k].value());
  }
  return out;
}

StatusOr<DracoRoundTrip> draco_round_trip(const TriangleMesh& mesh, const DracoOptions& options) {
  if (options.quantization_bits < 1 || options.quantization_bits > 30)
    return invalid_argument("Draco quantization bits must be 1..30, not " + std::to_string(options.quantization_bits));
  if (options.compression_level < 0 || options.compression_level > 10)
    return invalid_argument("Draco compression level must be 0..10, not " + std::to_string(options.compression_level));
  if (mesh.triangles.empty()) return invalid_mesh("Draco needs at least one triangle");
  if (mesh.positions.size() > std::numeric_limits<uint32_t>::max() / 2) return invalid_mesh("mesh too large for Draco");

  const std::unique_ptr<draco::Mesh> input = to_draco(mesh);
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, options.quantization_bits);
  // As draco_encoder does: speed = 10 - compression level, for encoding and decoding.
  const int speed = 10 - options.compression_level;
  encoder.SetSpeedOptions(speed, speed);

  DracoRoundTrip result;
  draco::EncoderBuffer buffer;
  auto start = std::chrono::steady_clock::now();
  const draco::Status encoded = encoder.EncodeMeshToBuffer(*input, &buffer);
  result.encode_ms = ms_since(start);
  if (!encoded.ok()) return internal_error("Draco could not encode: " + encoded.error_msg_string());
  result.encoded.assign(buffer.data(), buffer.size());

  start = std::chrono::steady_clock::now();
  SRCODEC_ASSIGN_OR_RETURN(result.decoded, draco_decode(result.encoded));
  result.decode_ms = ms_since(start);
  return result;
}

}  // namespace srcodec
