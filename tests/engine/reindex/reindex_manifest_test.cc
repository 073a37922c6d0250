// The manifest's LSH parameters: written and read back whole, and a manifest written before
// chain_probe_every existed reads as what those builds did (every column of a chain probed).
// The eps rule likewise: kept, absent in older manifests (read as unknown), an unknown one
// refused.
#include "engine/reindex/reindex_manifest.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace motif {
namespace {

ReindexManifest ALshManifest() {
  ReindexManifest manifest;
  manifest.version = 3;
  manifest.dir = VersionDirName(3);
  manifest.trellis.path = "v000003/trellis.mtr";
  manifest.paths.path = "v000003/paths.mpa";
  manifest.motifs.path = "v000003/motifs.json";
  manifest.params.exact = false;
  manifest.params.lsh.hashes_per_table = 16;
  manifest.params.lsh.bucket_width = 0.25f;
  manifest.params.lsh.chain_probe_every = 4;
  return manifest;
}

TEST(ReindexManifestTest, KeepsEveryLshParameter) {
  const ReindexManifest manifest = ALshManifest();
  auto read = ParseManifest(ManifestText(manifest), "manifest.json");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->params.lsh.chain_probe_every, 4u);
  EXPECT_TRUE(SameLshFamily(read->params.lsh, manifest.params.lsh));
  ReindexManifest other = manifest;
  other.params.lsh.chain_probe_every = 1;
  EXPECT_FALSE(SameLshFamily(other.params.lsh, manifest.params.lsh));
}

TEST(ReindexManifestTest, AManifestWithoutChainProbeEveryReadsAsEveryColumnProbing) {
  nlohmann::json text = nlohmann::json::parse(ManifestText(ALshManifest()));
  ASSERT_TRUE(text["params"]["lsh"].contains("chain_probe_every"));
  text["params"]["lsh"].erase("chain_probe_every");
  auto read = ParseManifest(text.dump(), "manifest.json");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->params.lsh.chain_probe_every, 1u);
  // Another field still may not be missing.
  text["params"]["lsh"].erase("chained_max_candidates");
  EXPECT_FALSE(ParseManifest(text.dump(), "manifest.json").ok());
}

TEST(ReindexManifestTest, KeepsTheEpsRuleAndReadsAnOlderManifestAsRuleUnknown) {
  ReindexManifest manifest = ALshManifest();
  manifest.params.eps_estimated = true;
  manifest.params.eps_rule = "joint-angle";
  manifest.params.eps_angle_degrees = 14.5;
  auto read = ParseManifest(ManifestText(manifest), "manifest.json");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->params.eps_rule, "joint-angle");
  EXPECT_EQ(read->params.eps_angle_degrees, 14.5);
  EXPECT_TRUE(read->params == manifest.params);
  ReindexManifest other = manifest;
  other.params.eps_angle_degrees = 12;
  EXPECT_FALSE(other.params == manifest.params);

  nlohmann::json text = nlohmann::json::parse(ManifestText(manifest));
  text["params"].erase("eps_rule");
  text["params"].erase("eps_angle");
  read = ParseManifest(text.dump(), "manifest.json");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->params.eps_rule, "");
  EXPECT_EQ(read->params.eps_angle_degrees, 0);

  text["params"]["eps_rule"] = "median";
  auto refused = ParseManifest(text.dump(), "manifest.json");
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.status().message().find("eps_rule"), std::string::npos);
}

}  // namespace
}  // namespace motif
