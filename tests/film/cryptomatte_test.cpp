// Cryptomatte: the hash and its float conversion against the specification's own examples, and
// the ranking filter on a rendered scene (coverage from all samples, filter-weighted).
#include "film/cryptomatte.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "accel/registry.h"
#include "core/error.h"
#include "film/aov.h"
#include "integrators/adaptive.h"
#include "integrators/registry.h"
#include "render/prepared_scene.h"
#include "render/renderer.h"
#include "tests/scene_builder.h"

namespace tray {
namespace {

using namespace tray::test;

uint32_t bits(float f) {
  return std::bit_cast<uint32_t>(f);
}

TEST(Cryptomatte, MurmurHash3MatchesReferenceValues) {
  // SMHasher's MurmurHash3_x86_32 with seed 0 (values published with the algorithm).
  EXPECT_EQ(murmurHash3_32(""), 0u);
  EXPECT_EQ(murmurHash3_32("", 1), 0x514e28b7u);
  EXPECT_EQ(murmurHash3_32("hello"), 0x248bfa47u);
  EXPECT_EQ(murmurHash3_32("The quick brown fox jumps over the lazy dog"), 0x2e4ff723u);
}

TEST(Cryptomatte, IdsMatchTheSpecificationManifestExamples) {
  // Cryptomatte specification, "Metadata" and "Manifest" sections.
  EXPECT_EQ(bits(cryptomatteId("bunny")), 0x13851a76u);
  EXPECT_EQ(bits(cryptomatteId("default")), 0x42c9679fu);
  EXPECT_EQ(bits(cryptomatteId("bunny_porcelain_mat")), 0xb24b26d4u);
}

TEST(Cryptomatte, MetadataKeysAreSevenHexDigitsOfTheTypeNameHash) {
  // The specification suggests "a hash of the type name" (its example keys are arbitrary).
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", murmurHash3_32("CryptoObject"));
  EXPECT_EQ(Cryptomatte::metadataKey("CryptoObject"), std::string(hex, 7));
  EXPECT_NE(Cryptomatte::metadataKey("CryptoObject"), Cryptomatte::metadataKey("CryptoMaterial"));
}

TEST(Cryptomatte, FloatConversionClampsTheExponent) {
  // Exponent 0 (zero, denormals) becomes 1; 255 (infinity, NaN) becomes 254; the rest is kept.
  EXPECT_EQ(bits(cryptomatteId(0x00000000u)), 0x00800000u);
  EXPECT_EQ(bits(cryptomatteId(0x80000001u)), 0x80800001u);
  EXPECT_EQ(bits(cryptomatteId(0x7f800000u)), 0x7f000000u);
  EXPECT_EQ(bits(cryptomatteId(0xffffffffu)), 0xff7fffffu);
  EXPECT_EQ(bits(cryptomatteId(0x3f800000u)), 0x3f800000u);
  for (uint32_t h : {0u, 0x7fffffffu, 0xff800000u, 0x12345678u}) {
    EXPECT_TRUE(std::isnormal(cryptomatteId(h))) << h;
  }
}

TEST(Cryptomatte, ParsesTheAovNames) {
  EXPECT_EQ(AovSet::parse("cryptomatte"),
            (std::vector<std::string>{"crypto_object", "crypto_material"}));
  EXPECT_EQ(AovSet::parse("depth,crypto_material"),
            (std::vector<std::string>{"depth", "crypto_material"}));
  auto all = AovSet::parse("all");
  EXPECT_NE(std::find(all.begin(), all.end(), "crypto_object"), all.end());
}

/// A floor (shape0) and a unit sphere (shape1) at (0, 1, -4), seen from (0, 1, 0).
struct TwoObjects {
  Scene scene;
  std::optional<PreparedScene> prepared;
  static constexpr int W = 33, H = 33;
  TwoObjects() {
    int floorMat = addMaterial(scene, diffuse(Color(0.2f)));
    scene.materials.back().name = "floor_mat";
    int ballMat = addMaterial(scene, diffuse(Color(0.9f, 0.5f, 0.1f)));
    addShape(scene, std::make_shared<Plane>(), Mat4::identity(), floorMat);
    addSphere(scene, {0, 1, -4}, 1.0f, ballMat);
    scene.finalize();
    prepared.emplace(scene, lookAt({0, 1, 0}, {0, 1, -1}, 1.0f), ImageSize{W, H});
  }
  Film render(RenderSettings settings, const std::string& aovs, int ranks = 6, int threads = 0) {
    RenderOptions opt;
    opt.aovs = AovSet::parse(aovs);
    opt.cryptomatteRanks = ranks;
    opt.threads = threads;
    return prepared->render(settings, opt);
  }
};

struct Rank {
  float id, coverage;
};

std::vector<Rank> ranks(const Film& film, const std::string& type, int x, int y, int count) {
  std::vector<Rank> out;
  for (int r = 0; r < count; ++r) {
    char name[32];
    std::snprintf(name, sizeof name, "%s%02d", type.c_str(), r / 2);
    const int layer = film.findLayer(name);
    EXPECT_GE(layer, 0) << name;
    if (layer < 0) return out;
    const float* p = film.pixel(layer, x, y) + 2 * (r % 2);
    out.push_back({p[0], p[1]});
  }
  return out;
}

RenderSettings gridSettings(const std::string& filter) {
  RenderSettings s;
  s.set("spp", 16);
  s.set("pixel-sampler", "grid");
  s.set("filter", filter);
  return s;
}

TEST(Cryptomatte, CoverageOfEveryPixelSumsToOneAndIsRankedByCoverage) {
  TwoObjects t;
  for (const char* filter : {"box", "tent", "gaussian"}) {
    Film film = t.render(gridSettings(filter), "cryptomatte");
    for (int y = 0; y < t.H; ++y)
      for (int x = 0; x < t.W; ++x)
        for (const char* type : {"CryptoObject", "CryptoMaterial"}) {
          auto r = ranks(film, type, x, y, 6);
          double sum = 0;
          for (size_t k = 0; k < r.size(); ++k) {
            sum += r[k].coverage;
            if (k > 0) {
              EXPECT_LE(r[k].coverage, r[k - 1].coverage) << x << "," << y;
            }
          }
          // Three ids at most (floor, sphere, nothing): all fit in 6 ranks.
          EXPECT_NEAR(sum, 1.0, 1e-5) << filter << " " << type << " " << x << "," << y;
        }
  }
}

TEST(Cryptomatte, IdsAreTheNameHashesAndEdgesHaveFractionalCoverage) {
  TwoObjects t;
  Film film = t.render(gridSettings("box"), "crypto_object,crypto_material");
  const float floor = cryptomatteId("shape0"), ball = cryptomatteId("shape1");
  // Centre: the sphere alone.
  auto centre = ranks(film, "CryptoObject", 16, 16, 2);
  EXPECT_EQ(bits(centre[0].id), bits(ball));
  EXPECT_FLOAT_EQ(centre[0].coverage, 1.0f);
  EXPECT_EQ(centre[1].coverage, 0.0f);
  EXPECT_EQ(bits(ranks(film, "CryptoMaterial", 16, 16, 1)[0].id), bits(cryptomatteId("material1")));
  // Bottom row: the floor alone; its material has a name.
  EXPECT_EQ(bits(ranks(film, "CryptoObject", 16, 32, 1)[0].id), bits(floor));
  EXPECT_EQ(bits(ranks(film, "CryptoMaterial", 16, 32, 1)[0].id), bits(cryptomatteId("floor_mat")));
  // Top row: nothing is hit: id 0 with full coverage (the specification's hash for no object).
  auto sky = ranks(film, "CryptoObject", 16, 0, 1);
  EXPECT_EQ(sky[0].id, 0.0f);
  EXPECT_FLOAT_EQ(sky[0].coverage, 1.0f);
  // (9, 20): the sphere's silhouette (radius ~7.8 px around the centre) over the floor. With a
  // 4x4 grid and a box filter, coverages are multiples of 1/16.
  auto edge = ranks(film, "CryptoObject", 9, 20, 3);
  std::set<uint32_t> ids = {bits(edge[0].id), bits(edge[1].id)};
  EXPECT_EQ(ids, (std::set<uint32_t>{bits(floor), bits(ball)}));
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(edge[k].coverage, 0.0f);
    EXPECT_LT(edge[k].coverage, 1.0f);
    EXPECT_FLOAT_EQ(edge[k].coverage * 16, std::round(edge[k].coverage * 16));
  }
  EXPECT_NEAR(edge[0].coverage + edge[1].coverage, 1.0f, 1e-6f);
  EXPECT_EQ(edge[2].coverage, 0.0f);
}

TEST(Cryptomatte, MetadataNamesEveryObjectAndMaterial) {
  TwoObjects t;
  Film film = t.render(gridSettings("box"), "cryptomatte");
  std::map<std::string, std::string> meta(film.metadata().begin(), film.metadata().end());
  const std::string obj = "cryptomatte/" + Cryptomatte::metadataKey("CryptoObject") + "/";
  const std::string mat = "cryptomatte/" + Cryptomatte::metadataKey("CryptoMaterial") + "/";
  EXPECT_EQ(meta[obj + "name"], "CryptoObject");
  EXPECT_EQ(meta[obj + "hash"], "MurmurHash3_32");
  EXPECT_EQ(meta[obj + "conversion"], "uint32_to_float32");
  char hex[9];
  std::snprintf(hex, sizeof hex, "%08x", bits(cryptomatteId("shape1")));
  EXPECT_NE(meta[obj + "manifest"].find(std::string("\"shape1\":\"") + hex + "\""),
            std::string::npos)
      << meta[obj + "manifest"];
  EXPECT_EQ(meta[mat + "name"], "CryptoMaterial");
  EXPECT_NE(meta[mat + "manifest"].find("\"floor_mat\""), std::string::npos);
}

TEST(Cryptomatte, RanksBeyondTheIdsPresentAreZeroAndOddRanksFit) {
  TwoObjects t;
  Film film = t.render(gridSettings("box"), "crypto_object", 3);
  EXPECT_GE(film.findLayer("CryptoObject01"), 0);
  EXPECT_LT(film.findLayer("CryptoObject02"), 0);
  EXPECT_LT(film.findLayer("CryptoMaterial00"), 0);
  auto r = ranks(film, "CryptoObject", 9, 20, 3);
  EXPECT_EQ(r[2].id, 0.0f);
  EXPECT_EQ(r[2].coverage, 0.0f);
  EXPECT_THROW(t.render(gridSettings("box"), "crypto_object", 0), Error);
}

TEST(Cryptomatte, SameImageForAnyThreadCount) {
  TwoObjects t;
  Film one = t.render(gridSettings("tent"), "cryptomatte", 6, 1);
  Film many = t.render(gridSettings("tent"), "cryptomatte", 6, 4);
  for (size_t l = 0; l < one.layers().size(); ++l)
    EXPECT_EQ(one.layers()[l].data, many.layers()[l].data) << one.layers()[l].name;
}

TEST(Cryptomatte, AdaptiveWeighsItsCornerSamples) {
  TwoObjects t;
  RenderSettings s;
  s.set("integrator", "adaptive");
  s.set("aa-depth", 3);
  s.set("aa-threshold", 0.0f);  // subdivide everywhere: every pixel gets 81 lattice points
  Film film = t.render(s, "crypto_object");
  for (int y = 0; y < t.H; ++y)
    for (int x = 0; x < t.W; ++x) {
      auto r = ranks(film, "CryptoObject", x, y, 6);
      double sum = 0;
      for (const Rank& k : r) sum += k.coverage;
      EXPECT_NEAR(sum, 1.0, 1e-5) << x << "," << y;
    }
  auto edge = ranks(film, "CryptoObject", 9, 20, 2);
  EXPECT_GT(edge[1].coverage, 0.0f);
  EXPECT_LT(edge[0].coverage, 1.0f);
}

}  // namespace
}  // namespace tray
