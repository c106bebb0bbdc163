// The public decoder (<srcodec/decoder.h>) as a library user meets it: the
// same meshes as the codec's own decode, prefixes, levels, inspect and
// truncate, and a Status for every kind of bad call.
#include <srcodec/decoder.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "codec/srm_codec.h"
#include "format/file_io.h"
#include "format/srm/srm_file.h"
#include "tests/test_util.h"

namespace srcodec {
namespace {

std::vector<uint8_t> sample_file(const std::string& name) {
  StatusOr<std::string> bytes = read_file_bytes(test::source_path("tests/data/" + name));
  EXPECT_TRUE(bytes.ok()) << bytes.status().message();
  return bytes.ok() ? std::vector<uint8_t>(bytes->begin(), bytes->end()) : std::vector<uint8_t>{};
}

// The codec's own decode of the first `size` bytes, for comparison.
DecodedSrm codec_decode(const std::vector<uint8_t>& file, size_t size, int level) {
  StatusOr<SrmFile> parsed = parse_srm(file.data(), size);
  EXPECT_TRUE(parsed.ok()) << parsed.status().message();
  SrmDecodeOptions options;
  options.level = level;
  StatusOr<DecodedSrm> decoded = decode_srm(parsed.value(), options);
  EXPECT_TRUE(decoded.ok()) << decoded.status().message();
  return std::move(decoded).value();
}

void expect_same_mesh(const Mesh& mesh, const TriangleMesh& expected) {
  ASSERT_EQ(mesh.vertex_count(), expected.positions.size());
  ASSERT_EQ(mesh.triangle_count(), expected.triangles.size());
  for (size_t v = 0; v < expected.positions.size(); ++v)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(mesh.positions[3 * v + k], expected.positions[v][k]) << v;
  for (size_t t = 0; t < expected.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(mesh.triangles[3 * t + k], static_cast<uint32_t>(expected.triangles[t][k]));
}

TEST(DecoderApi, EveryLevelAsTheCodecDecodesIt) {
  const std::vector<uint8_t> file = sample_file("spot_default.srm");
  for (int level = -1; level <= 4; ++level) {
    DecodeOptions options;
    options.level = level;
    StatusOr<Decoded> d = decode(file.data(), file.size(), options);
    ASSERT_TRUE(d.ok()) << d.status().message();
    const DecodedSrm expected = codec_decode(file, file.size(), level);
    EXPECT_EQ(d->level, level < 0 ? 4 : level);
    EXPECT_EQ(d->bytes_used, expected.bytes_used);
    EXPECT_EQ(d->last_complete_plane, expected.last_plane);
    EXPECT_FALSE(d->base_cut);
    expect_same_mesh(d->mesh, expected.mesh);
  }
}

TEST(DecoderApi, MaxBytesDecodesThePrefix) {
  const std::vector<uint8_t> file = sample_file("spot_default.srm");
  for (size_t cut : {size_t{400}, size_t{777}, size_t{1500}}) {
    DecodeOptions options;
    options.max_bytes = cut;
    StatusOr<Decoded> d = decode(file.data(), file.size(), options);
    ASSERT_TRUE(d.ok()) << d.status().message();
    EXPECT_LE(d->bytes_used, cut);
    expect_same_mesh(d->mesh, codec_decode(file, cut, -1).mesh);
    // The same bytes handed over as a shorter buffer.
    StatusOr<Decoded> shorter = decode(file.data(), cut);
    ASSERT_TRUE(shorter.ok()) << shorter.status().message();
    EXPECT_EQ(shorter->mesh.positions, d->mesh.positions);
  }
  // Past the end: the whole file.
  DecodeOptions past;
  past.max_bytes = file.size() + 1000;
  StatusOr<Decoded> all = decode(file.data(), file.size(), past);
  ASSERT_TRUE(all.ok()) << all.status().message();
  EXPECT_EQ(all->bytes_used, file.size());
}

TEST(DecoderApi, ThreadsOrNotTheSameMesh) {
  const std::vector<uint8_t> file = sample_file("bunny_npm_default.srm");
  DecodeOptions one;
  one.threads = false;
  StatusOr<Decoded> a = decode(file.data(), file.size(), one);
  StatusOr<Decoded> b = decode(file.data(), file.size());
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->mesh.positions, b->mesh.positions);
  EXPECT_EQ(a->mesh.triangles, b->mesh.triangles);
}

TEST(DecoderApi, BadCallsGiveAStatus) {
  const std::vector<uint8_t> file = sample_file("spot_default.srm");
  StatusOr<Decoded> empty = decode(nullptr, 0);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.status().message().find("no bytes"), std::string::npos) << empty.status().message();
  StatusOr<Decoded> null = decode(nullptr, 10);
  ASSERT_FALSE(null.ok());
  EXPECT_EQ(null.status().code(), StatusCode::kInvalidArgument);

  DecodeOptions beyond;
  beyond.level = 9;
  StatusOr<Decoded> high = decode(file.data(), file.size(), beyond);
  ASSERT_FALSE(high.ok());
  EXPECT_NE(high.status().message().find("levels 0..4"), std::string::npos) << high.status().message();
  beyond.level = -2;
  EXPECT_EQ(decode(file.data(), file.size(), beyond).status().code(), StatusCode::kInvalidArgument);
  beyond.level = 13;
  EXPECT_EQ(decode(file.data(), file.size(), beyond).status().code(), StatusCode::kInvalidArgument);

  DecodeOptions none;
  none.max_vertices = 0;
  EXPECT_EQ(decode(file.data(), file.size(), none).status().code(), StatusCode::kInvalidArgument);
  // Level 4 has 30978 vertices: refused before decoding, level 3 is not.
  DecodeOptions few;
  few.max_vertices = 10000;
  StatusOr<Decoded> refused = decode(file.data(), file.size(), few);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("over the limit"), std::string::npos) << refused.status().message();
  few.level = 3;
  EXPECT_TRUE(decode(file.data(), file.size(), few).ok());

  const std::vector<uint8_t> junk = {'n', 'o', 't', ' ', 's', 'r', 'm', '!', 0, 0, 0, 0, 0, 0, 0, 0};
  StatusOr<Decoded> bad = decode(junk.data(), junk.size());
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().code(), StatusCode::kParseError);
}

// Every prefix of a small file decodes or says why not; none crashes.
TEST(DecoderApi, EveryPrefixDecodesOrFailsCleanly) {
  const std::vector<uint8_t> file = sample_file("golden_v2.srm");
  size_t decoded = 0;
  for (size_t n = 1; n <= file.size(); n += 7) {
    StatusOr<Decoded> d = decode(file.data(), n);
    if (!d.ok()) {
      EXPECT_FALSE(d.status().message().empty());
      continue;
    }
    ++decoded;
    EXPECT_LE(d->bytes_used, n);
  }
  EXPECT_GT(decoded, file.size() / 7 / 2);  // all but the prefixes inside the header
}

TEST(DecoderApi, InspectSaysWhereEachLevelCanBeDrawn) {
  const std::vector<uint8_t> file = sample_file("spot_default.srm");
  StatusOr<FileInfo> info = inspect(file.data(), file.size());
  ASSERT_TRUE(info.ok()) << info.status().message();
  EXPECT_EQ(info->version, 2);
  EXPECT_EQ(info->file_bytes, file.size());
  EXPECT_EQ(info->declared_bytes, file.size());
  EXPECT_EQ(info->input_vertices, 2930u);
  EXPECT_EQ(info->levels, 4);
  EXPECT_EQ(info->base_vertices, 123u);
  ASSERT_EQ(info->level_info.size(), 5u);
  EXPECT_EQ(info->level_info[0].vertices, 123u);
  EXPECT_EQ(info->level_info[4].vertices, 30978u);
  uint64_t coefficients = 0;
  for (int l = 0; l <= 4; ++l) {
    coefficients += info->level_info[l].coefficient_bytes;
    // From drawable_from on, the level decodes; one byte less, it does not.
    DecodeOptions at;
    at.level = l;
    at.max_bytes = info->level_info[l].drawable_from;
    StatusOr<Decoded> d = decode(file.data(), file.size(), at);
    ASSERT_TRUE(d.ok()) << d.status().message();
    EXPECT_EQ(d->level, l);
    if (l > 0) {
      at.max_bytes -= 1;
      StatusOr<Decoded> before = decode(file.data(), file.size(), at);
      ASSERT_TRUE(before.ok()) << before.status().message();
      EXPECT_EQ(before->level, l - 1);
    }
  }
  EXPECT_EQ(info->level_info[4].drawable_from + coefficients, file.size());
  ASSERT_FALSE(info->planes.empty());
  EXPECT_EQ(info->planes.front().plane, info->top_plane);
  EXPECT_EQ(info->planes.back().end, file.size());
  for (size_t k = 1; k < info->planes.size(); ++k) EXPECT_GE(info->planes[k].end, info->planes[k - 1].end);

  // A prefix that holds the header says how large the whole is.
  StatusOr<FileInfo> prefix = inspect(file.data(), 600);
  ASSERT_TRUE(prefix.ok()) << prefix.status().message();
  EXPECT_EQ(prefix->file_bytes, 600u);
  EXPECT_EQ(prefix->declared_bytes, file.size());
  EXPECT_FALSE(inspect(file.data(), 10).ok());
}

TEST(DecoderApi, TruncateKeepsAValidSmallerFile) {
  const std::vector<uint8_t> file = sample_file("spot_default.srm");
  StatusOr<std::vector<uint8_t>> small = truncate(file.data(), file.size(), 1500);
  ASSERT_TRUE(small.ok()) << small.status().message();
  EXPECT_LE(small->size(), 1500u);
  EXPECT_GT(small->size(), 1480u);
  StatusOr<Decoded> d = decode(small->data(), small->size());
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_EQ(d->bytes_used, small->size());

  StatusOr<std::vector<uint8_t>> same = truncate(file.data(), file.size(), file.size() + 5);
  ASSERT_TRUE(same.ok()) << same.status().message();
  EXPECT_EQ(same.value(), file);

  StatusOr<std::vector<uint8_t>> tiny = truncate(file.data(), file.size(), 100);
  ASSERT_FALSE(tiny.ok());
  EXPECT_NE(tiny.status().message().find("header, base mesh and refinement flags"), std::string::npos)
      << tiny.status().message();
  EXPECT_FALSE(truncate(nullptr, 0, 1000).ok());
}

}  // namespace
}  // namespace srcodec

namespace srcodec {
namespace {

// The base crease each crease edge of a finer level refines: from a base
// vertex along the crease edges through new vertices (each on one crease,
// so on two of its edges) to the next base vertex.
std::vector<std::array<uint32_t, 2>> base_creases_refined(const std::vector<uint32_t>& edges, size_t base_vertices) {
  std::map<uint32_t, std::vector<uint32_t>> next;
  for (size_t k = 0; k < edges.size(); k += 2) {
    next[edges[k]].push_back(edges[k + 1]);
    next[edges[k + 1]].push_back(edges[k]);
  }
  std::vector<std::array<uint32_t, 2>> out;
  for (const auto& [a, ends] : next) {
    if (a >= base_vertices) continue;
    for (uint32_t at : ends) {
      uint32_t from = a;
      while (at >= base_vertices && next[at].size() == 2) {
        const uint32_t after = next[at][0] == from ? next[at][1] : next[at][0];
        from = at;
        at = after;
      }
      if (a < at) out.push_back({a, at});
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

// tests/data/creases_v3.srm (a sphere with creases on 10 of its 30 base
// edges): decode gives the crease edges of the mesh of its level, those
// the codec's decode gives, each an edge of the mesh, which chain up into
// the base creases; a prefix cut inside them gives the base mesh, inspect
// counts the base creases.
TEST(DecoderApi, CreasesAreEdgesOfTheMeshOfTheLevel) {
  const std::vector<uint8_t> file = sample_file("creases_v3.srm");
  const SrmFile layout = parse_srm(file.data(), file.size()).value();
  ASSERT_TRUE(layout.header.has_creases);
  std::vector<std::array<uint32_t, 2>> base;
  std::vector<uint32_t> finest;
  for (int level = 0; level <= 3; ++level) {
    DecodeOptions options;
    options.level = level;
    StatusOr<Decoded> d = decode(file.data(), file.size(), options);
    ASSERT_TRUE(d.ok()) << d.status().message();
    const DecodedSrm expected = codec_decode(file, file.size(), level);
    ASSERT_EQ(d->crease_edges.size(), 2 * expected.crease_edges.size());
    for (size_t k = 0; k < expected.crease_edges.size(); ++k) {
      EXPECT_EQ(d->crease_edges[2 * k], static_cast<uint32_t>(expected.crease_edges[k][0]));
      EXPECT_EQ(d->crease_edges[2 * k + 1], static_cast<uint32_t>(expected.crease_edges[k][1]));
    }
    EXPECT_FALSE(d->creases_cut);
    expect_same_mesh(d->mesh, expected.mesh);
    std::set<std::array<uint32_t, 2>> mesh_edges;
    for (size_t t = 0; t < d->mesh.triangle_count(); ++t)
      for (int c = 0; c < 3; ++c) {
        const uint32_t a = d->mesh.triangles[3 * t + c], b = d->mesh.triangles[3 * t + (c + 1) % 3];
        mesh_edges.insert({std::min(a, b), std::max(a, b)});
      }
    std::vector<std::array<uint32_t, 2>> pairs;
    for (size_t k = 0; k < d->crease_edges.size(); k += 2) {
      pairs.push_back({d->crease_edges[k], d->crease_edges[k + 1]});
      EXPECT_LT(pairs.back()[0], pairs.back()[1]);
      EXPECT_TRUE(mesh_edges.count(pairs.back())) << level << ": " << k;
    }
    EXPECT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    const std::vector<std::array<uint32_t, 2>> chains =
        base_creases_refined(d->crease_edges, layout.header.base_vertices);
    if (level == 0) {
      ASSERT_EQ(d->crease_edges.size(), 20u);
      base = chains;
    } else {
      EXPECT_GT(d->crease_edges.size(), 20u) << level;  // some were split
    }
    EXPECT_EQ(chains, base) << level;
    finest = d->crease_edges;
  }
  // The finest level by default, on one thread or two.
  for (bool threads : {false, true}) {
    DecodeOptions options;
    options.threads = threads;
    EXPECT_EQ(decode(file.data(), file.size(), options)->crease_edges, finest);
  }
  DecodeOptions cut;
  cut.max_bytes = layout.creases.offset + layout.creases.declared - 1;
  StatusOr<Decoded> d = decode(file.data(), file.size(), cut);
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_TRUE(d->creases_cut);
  EXPECT_FALSE(d->base_cut);
  EXPECT_EQ(d->level, 0);
  EXPECT_TRUE(d->crease_edges.empty());
  EXPECT_EQ(d->mesh.triangle_count(), layout.header.base_triangles);

  StatusOr<FileInfo> info = inspect(file.data(), file.size());
  ASSERT_TRUE(info.ok()) << info.status().message();
  EXPECT_EQ(info->version, 3);
  EXPECT_EQ(info->crease_edges, 10);
  EXPECT_EQ(info->crease_bytes, layout.creases.declared);
  EXPECT_EQ(inspect(file.data(), cut.max_bytes)->crease_edges, -1);
  EXPECT_EQ(inspect(file.data(), cut.max_bytes + 1)->crease_edges, 10);
  const std::vector<uint8_t> spot = sample_file("spot_default.srm");
  EXPECT_EQ(inspect(spot.data(), spot.size())->crease_edges, 0);
  EXPECT_EQ(inspect(spot.data(), spot.size())->crease_bytes, 0u);
  // truncate keeps them.
  const std::vector<uint8_t> small = truncate(file.data(), file.size(), 800).value();
  EXPECT_EQ(decode(small.data(), small.size())->crease_edges, finest);
}

}  // namespace
}  // namespace srcodec
