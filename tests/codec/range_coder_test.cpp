#include "codec/range_coder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace srcodec {
namespace {

struct Symbol {
  int bit;
  int model;  // index into the model table; -1 = raw bits
  uint32_t raw = 0;
  int raw_bits = 0;
};

// A mixed sequence: modeled bits with per-model skew, and raw runs.
std::vector<Symbol> random_symbols(size_t n, int models, uint32_t seed, bool with_raw) {
  std::mt19937 rng(seed);
  std::vector<double> p1(models);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double& p : p1) {
    const double r = u(rng);
    p = r < 0.3 ? r * 0.05 : (r > 0.7 ? 1.0 - (1.0 - r) * 0.05 : r);  // some very skewed
  }
  std::vector<Symbol> out;
  for (size_t i = 0; i < n; ++i) {
    if (with_raw && rng() % 10 == 0) {
      const int bits = static_cast<int>(rng() % 33);
      const uint32_t v = bits == 0 ? 0 : static_cast<uint32_t>(rng()) >> (32 - bits);
      out.push_back({0, -1, v, bits});
      continue;
    }
    const int m = static_cast<int>(rng() % models);
    out.push_back({u(rng) < p1[m] ? 1 : 0, m});
  }
  return out;
}

std::vector<uint8_t> encode_all(const std::vector<Symbol>& s, int models) {
  std::vector<BitModel> table(models);
  ArithmeticEncoder enc;
  for (const Symbol& x : s) {
    if (x.model < 0) {
      enc.encode_raw(x.raw, x.raw_bits);
    } else {
      enc.encode(x.bit, table[x.model]);
    }
  }
  return enc.finish();
}

// Decodes symbols with the same model sequence; returns how many matched while
// ok() held, and fails the test if any symbol decoded under ok() differs.
size_t decode_checked(const std::vector<Symbol>& s, int models, const uint8_t* data, size_t size) {
  std::vector<BitModel> table(models);
  ArithmeticDecoder dec(data, size);
  size_t good = 0;
  for (const Symbol& x : s) {
    bool same;
    if (x.model < 0) {
      same = dec.decode_raw(x.raw_bits) == x.raw;
    } else {
      same = dec.decode(table[x.model]) == x.bit;
    }
    if (!dec.ok()) break;
    EXPECT_TRUE(same) << "symbol " << good << " decoded wrong while ok()";
    if (!same) break;
    ++good;
  }
  return good;
}

TEST(RangeCoder, EmptyStream) {
  ArithmeticEncoder enc;
  EXPECT_TRUE(enc.empty());
  EXPECT_TRUE(enc.finish().empty());
  ArithmeticDecoder dec(nullptr, 0);
  EXPECT_TRUE(dec.ok());
  BitModel m;
  dec.decode(m);
  EXPECT_FALSE(dec.ok());  // nothing can be decided from no bytes
}

TEST(RangeCoder, RoundTripRandomModels) {
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    const int models = 1 + static_cast<int>(seed % 7);
    const auto s = random_symbols(5000 + seed * 731, models, seed, seed % 2 == 0);
    const auto bytes = encode_all(s, models);
    EXPECT_EQ(decode_checked(s, models, bytes.data(), bytes.size()), s.size()) << "seed " << seed;
  }
}

TEST(RangeCoder, SingleSymbolStreamsAreShort) {
  for (int bit = 0; bit < 2; ++bit) {
    ArithmeticEncoder enc;
    BitModel m;
    enc.encode(bit, m);
    EXPECT_FALSE(enc.empty());
    const auto bytes = enc.finish();
    EXPECT_GE(bytes.size(), 1u);
    EXPECT_LE(bytes.size(), 2u);
    ArithmeticDecoder dec(bytes.data(), bytes.size());
    BitModel d;
    EXPECT_EQ(dec.decode(d), bit);
    EXPECT_TRUE(dec.ok());
  }
}

TEST(RangeCoder, FlushOverheadIsAtMostTwoBytesAboveEntropy) {
  // Equiprobable raw bits: the ideal is exactly bits / 8 bytes.
  std::mt19937 rng(5);
  for (int n : {1, 7, 8, 9, 100, 1000, 4096}) {
    ArithmeticEncoder enc;
    std::vector<uint32_t> bits(n);
    for (auto& b : bits) b = rng() & 1u;
    for (uint32_t b : bits) enc.encode_raw(b, 1);
    const auto bytes = enc.finish();
    EXPECT_LE(bytes.size(), static_cast<size_t>((n + 7) / 8 + 2)) << n << " bits";
    ArithmeticDecoder dec(bytes.data(), bytes.size());
    for (uint32_t b : bits) ASSERT_EQ(dec.decode_raw(1), b);
    EXPECT_TRUE(dec.ok());
  }
}

TEST(RangeCoder, RawBitsRoundTrip) {
  std::mt19937 rng(9);
  std::vector<std::pair<uint32_t, int>> values;
  ArithmeticEncoder enc;
  for (int i = 0; i < 20000; ++i) {
    const int bits = static_cast<int>(rng() % 33);
    const uint32_t v = bits == 0 ? 0 : static_cast<uint32_t>(rng()) >> (32 - bits);
    values.emplace_back(v, bits);
    enc.encode_raw(v, bits);
  }
  enc.encode_raw(0xFFFFFFFFu, 32);
  enc.encode_raw(0u, 32);
  const auto bytes = enc.finish();
  ArithmeticDecoder dec(bytes.data(), bytes.size());
  for (const auto& [v, bits] : values) ASSERT_EQ(dec.decode_raw(bits), v);
  EXPECT_EQ(dec.decode_raw(32), 0xFFFFFFFFu);
  EXPECT_EQ(dec.decode_raw(32), 0u);
  EXPECT_TRUE(dec.ok());
}

TEST(RangeCoder, SkewedSourceNearEntropy) {
  // Within 3% of the entropy for p = 0.05 and 0.5. At p = 0.995 (0.045 bit per
  // symbol) the estimation noise of a 1/128-rate model dominates (5.7%): allow 10%.
  for (double p1 : {0.05, 0.5, 0.995}) {
    const double tolerance = p1 > 0.99 ? 1.10 : 1.03;
    const size_t n = 1000000;
    std::mt19937 rng(17);
    std::bernoulli_distribution d(p1);
    std::vector<uint8_t> bits(n);
    for (auto& b : bits) b = d(rng);
    ArithmeticEncoder enc;
    BitModel m;
    for (uint8_t b : bits) enc.encode(b, m);
    const auto bytes = enc.finish();
    const double h = -(p1 * std::log2(p1) + (1 - p1) * std::log2(1 - p1));
    const double ratio = bytes.size() * 8.0 / (h * n);
    EXPECT_LT(ratio, tolerance) << "p1 = " << p1;
    EXPECT_GT(ratio, 0.98) << "p1 = " << p1;
    ArithmeticDecoder dec(bytes.data(), bytes.size());
    BitModel dm;
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(dec.decode(dm), bits[i]) << i;
    EXPECT_TRUE(dec.ok());
  }
}

TEST(RangeCoder, CarryPropagationOnLongFFRuns) {
  // Highly probable 1s push low up into long runs of 0xFF, exercising carries.
  std::mt19937 rng(3);
  std::vector<int> bits;
  for (int i = 0; i < 200000; ++i) bits.push_back(rng() % 1000 != 0 ? 1 : 0);
  ArithmeticEncoder enc;
  BitModel m;
  for (int b : bits) enc.encode(b, m);
  const auto bytes = enc.finish();
  ArithmeticDecoder dec(bytes.data(), bytes.size());
  BitModel dm;
  for (int b : bits) ASSERT_EQ(dec.decode(dm), b);
  EXPECT_TRUE(dec.ok());
}

TEST(RangeCoder, EveryPrefixDecodesCorrectlyWhileOk) {
  for (uint32_t seed = 100; seed < 106; ++seed) {
    const int models = 3;
    const auto s = random_symbols(600, models, seed, seed % 2 == 1);
    const auto bytes = encode_all(s, models);
    size_t previous = 0;
    for (size_t len = 0; len <= bytes.size(); ++len) {
      // A copy of exactly `len` bytes, so reading past it would be caught by ASan.
      std::vector<uint8_t> prefix(bytes.begin(), bytes.begin() + len);
      const size_t good = decode_checked(s, models, prefix.data(), prefix.size());
      EXPECT_GE(good, previous) << "longer prefix decoded fewer symbols, len " << len;
      previous = good;
      if (len + 4 <= bytes.size()) {
        EXPECT_LT(good, s.size()) << "a prefix missing 4+ bytes claimed the whole stream";
      }
    }
    EXPECT_EQ(previous, s.size());
  }
}

TEST(RangeCoder, GarbageNeverCrashes) {
  std::mt19937 rng(77);
  for (int t = 0; t < 1000; ++t) {
    std::vector<uint8_t> buf(rng() % 64);
    for (auto& b : buf) b = static_cast<uint8_t>(rng());
    ArithmeticDecoder dec(buf.data(), buf.size());
    std::vector<BitModel> models(4);
    uint64_t sum = 0;
    for (int i = 0; i < 2000; ++i) {
      if (i % 5 == 0) {
        sum += dec.decode_raw(static_cast<int>(rng() % 33));
      } else {
        sum += static_cast<uint64_t>(dec.decode(models[rng() % 4]));
      }
    }
    EXPECT_LE(dec.bytes_consumed(), buf.size());
    EXPECT_GE(sum, 0u);  // the values themselves are arbitrary
  }
}

}  // namespace
}  // namespace srcodec
