// End-to-end tests of `motifmine words`, `search`, `classify` and `segment` with the built binary,
// as a user would run them on a small synthetic archive: the files and documents they write, reuse,
// a query exported as BVH finding where it came from, and clear errors on bad input.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "tests/testing/byte_files.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunTool;

nlohmann::json ReadJson(const std::string& path) {
  auto text = ReadFileToString(path);
  EXPECT_TRUE(text.ok()) << path;
  return text.ok() ? nlohmann::json::parse(*text) : nlohmann::json();
}

// A small archive and its words (fast options), shared by the tests of this file.
class WordsCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new testing::TempDir();
    archive_ = dir_->File("s.mfs");
    ASSERT_EQ(RunTool("synth " + archive_ + " --frames 24000 --motifs 2 --seed 3 " +
                      "--clip-seconds-min 15 --clip-seconds-max 25 --quiet")
                  .exit_code,
              0);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string WordsArgs() {
    return " --epochs 2 --channels 16 --dims 8 --motifs 12 --quiet";
  }
  static testing::TempDir* dir_;
  static std::string archive_;
};

testing::TempDir* WordsCliTest::dir_ = nullptr;
std::string WordsCliTest::archive_;

TEST_F(WordsCliTest, WordsWritesItsFilesThenReusesThem) {
  RunResult help = RunTool("words --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("usage: motifmine words"), std::string::npos);
  RunResult first = RunTool("words " + archive_ + WordsArgs() + " --json " + dir_->File("w.json"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("embedding    trained"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("held out     triplet accuracy"), std::string::npos);
  for (const char* ext : {".mwe", ".mwm", ".mws"}) {
    EXPECT_TRUE(testing::FileExists(dir_->File(std::string("s") + ext))) << ext;
  }
  const nlohmann::json json = ReadJson(dir_->File("w.json"));
  EXPECT_EQ(json["embedding"], "trained");
  EXPECT_EQ(json["motifs"], 12);
  EXPECT_EQ(json["training"]["epoch_loss"].size(), 2u);
  EXPECT_GT(json["words"].get<uint64_t>(), 1000u);
  RunResult second = RunTool("words " + archive_ + WordsArgs());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("embedding    reused"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("signatures   "), std::string::npos);
  EXPECT_NE(second.output.find(", reused"), std::string::npos) << second.output;
}

TEST_F(WordsCliTest, SearchFindsAnExportedRangeAndTheWholeTake) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  // A clip range, searched from inside the archive: its own windows are left out.
  RunResult range = RunTool("search " + archive_ + " --clip synth_000001 --start 600 --end 1200 " +
                            "--top 3 --out " + dir_->File("range") + " --quiet");
  ASSERT_EQ(range.exit_code, 0) << range.output;
  nlohmann::json json = ReadJson(dir_->File("range/search.json"));
  EXPECT_EQ(json["query"]["kind"], "clip-range");
  EXPECT_EQ(json["query"]["words"], 27);  // words [30, 57) read frames [600, 1196)
  ASSERT_EQ(json["matches"].size(), 3u);
  EXPECT_LE(json["matches"][0]["distance"].get<double>(),
            json["matches"][1]["distance"].get<double>());
  EXPECT_TRUE(testing::FileExists(dir_->File("range/search.html")));
  // The same range exported as BVH and searched as a file: found where it came from.
  ASSERT_EQ(RunTool("export " + archive_ + " --clip synth_000001 --start 600 --end 1200 --out " +
                    dir_->File("q.bvh"))
                .exit_code,
            0);
  RunResult file = RunTool("search " + archive_ + " --query " + dir_->File("q.bvh") +
                           " --top 2 --out " + dir_->File("file") + " --quiet");
  ASSERT_EQ(file.exit_code, 0) << file.output;
  json = ReadJson(dir_->File("file/search.json"));
  EXPECT_EQ(json["query"]["kind"], "file");
  ASSERT_FALSE(json["matches"].empty());
  EXPECT_EQ(json["matches"][0]["clip"], "synth_000001");
  const int64_t start = json["matches"][0]["start"].get<int64_t>();
  const int64_t end = json["matches"][0]["end"].get<int64_t>();
  EXPECT_LT(std::max<int64_t>(start, 600), std::min<int64_t>(end, 1200)) << file.output;
  // The page draws the query file's keyframes above the matches, as it draws a clip range's.
  const std::string page = ReadFileToString(dir_->File("file/search.html")).value();
  const size_t matches_at = page.find("id=\"matches\"");
  ASSERT_NE(matches_at, std::string::npos);
  const std::string query_part = page.substr(0, matches_at);
  EXPECT_NE(query_part.find("file " + dir_->File("q.bvh") + ", 600 frames"), std::string::npos);
  size_t figures = 0;
  for (size_t at = query_part.find("<svg class=\"fig\""); at != std::string::npos;
       at = query_part.find("<svg class=\"fig\"", at + 1)) {
    ++figures;
  }
  EXPECT_EQ(figures, 5u) << "the query's keyframes";
  // The whole take: every other take ranked.
  RunResult whole = RunTool("search " + archive_ + " --clip synth_000001 --top 100 --out " +
                            dir_->File("whole") + " --quiet");
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  json = ReadJson(dir_->File("whole/search.json"));
  EXPECT_EQ(json["query"]["kind"], "take");
  for (const auto& match : json["matches"]) EXPECT_NE(match["clip"], "synth_000001");
}

// Whether two matches of search.json read a frame in common.
bool MatchesOverlap(const nlohmann::json& a, const nlohmann::json& b) {
  return a["clip"] == b["clip"] && a["start"].get<uint64_t>() < b["end"].get<uint64_t>() &&
         b["start"].get<uint64_t>() < a["end"].get<uint64_t>();
}

TEST_F(WordsCliTest, SearchKeepsSeveralWindowsATakeNeverTheQuery) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  RunResult range = RunTool("search " + archive_ + " --clip synth_000001 --start 600 --end 1200 " +
                            "--top 20 --out " + dir_->File("several"));
  ASSERT_EQ(range.exit_code, 0) << range.output;
  EXPECT_NE(range.output.find("windows of synth_000001 sharing a frame with frames 600-1200"),
            std::string::npos)
      << range.output;
  const nlohmann::json json = ReadJson(dir_->File("several/search.json"));
  EXPECT_EQ(json["version"], 2);
  EXPECT_EQ(json["overlap"], "shared source frame");
  EXPECT_EQ(json["query"]["word_start"], 600);
  EXPECT_EQ(json["query"]["word_end"], 1196);
  EXPECT_EQ(json["query"]["padded"], false);
  const nlohmann::json& matches = json["matches"];
  ASSERT_EQ(matches.size(), 20u);  // of 27 non-overlapping windows in all
  std::map<std::string, uint32_t> per_take;
  for (size_t rank = 0; rank < matches.size(); ++rank) {
    const nlohmann::json& match = matches[rank];
    EXPECT_EQ(match["rank_in_take"], ++per_take[match["clip"].get<std::string>()]);
    EXPECT_FALSE(match["clip"] == "synth_000001" && match["start"].get<uint64_t>() < 1200 &&
                 match["end"].get<uint64_t>() > 600)
        << "the query found itself at " << match["start"];
    for (size_t other = 0; other < rank; ++other) {
      EXPECT_FALSE(MatchesOverlap(match, matches[other])) << rank << " and " << other;
    }
    if (rank > 0) {
      EXPECT_LE(matches[rank - 1]["distance"], match["distance"]);
    }
  }
  EXPECT_TRUE(std::any_of(per_take.begin(), per_take.end(), [](const auto& take) {
    return take.second > 1;
  })) << "several windows of one take";
  EXPECT_NE(range.output.find("(its take's #2)"), std::string::npos) << range.output;
}

TEST_F(WordsCliTest, SearchPadsAQueryShorterThanOneWord) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  // 64 frames (0.53 s) of a take: the word centred on them, [600, 676).
  RunResult range = RunTool("search " + archive_ + " --clip synth_000001 --start 600 --end 664 " +
                            "--top 5 --out " + dir_->File("short"));
  ASSERT_EQ(range.exit_code, 0) << range.output;
  EXPECT_NE(range.output.find("note         the query is 0.53 s (frames 600-664), shorter than "
                              "one motion word (0.63 s, 76 frames): padded to 0.63 s by taking "
                              "the word centred on it, frames 600-676"),
            std::string::npos)
      << range.output;
  nlohmann::json json = ReadJson(dir_->File("short/search.json"));
  EXPECT_EQ(json["query"]["words"], 1);
  EXPECT_EQ(json["query"]["padded"], true);
  EXPECT_EQ(json["query"]["word_start"], 600);
  EXPECT_EQ(json["query"]["word_end"], 676);
  ASSERT_EQ(json["matches"].size(), 5u);
  for (const auto& match : json["matches"]) {
    EXPECT_EQ(match["words"], 1);
    EXPECT_FALSE(match["clip"] == "synth_000001" && match["start"].get<uint64_t>() < 676 &&
                 match["end"].get<uint64_t>() > 600);
  }
  // The same frames as a BVH file: held at either end to one word, and found where they came
  // from (the file query does not know its origin, so that window may be found).
  ASSERT_EQ(RunTool("export " + archive_ + " --clip synth_000001 --start 600 --end 664 --out " +
                    dir_->File("short.bvh"))
                .exit_code,
            0);
  RunResult file = RunTool("search " + archive_ + " --query " + dir_->File("short.bvh") +
                           " --top 3 --out " + dir_->File("short_file"));
  ASSERT_EQ(file.exit_code, 0) << file.output;
  EXPECT_NE(file.output.find("note         the query is 0.53 s (64 frames), shorter than one "
                             "motion word (0.63 s, 76 frames): padded to 0.63 s by holding its "
                             "first frame for 6 frames and its last for 6"),
            std::string::npos)
      << file.output;
  json = ReadJson(dir_->File("short_file/search.json"));
  EXPECT_EQ(json["query"]["words"], 1);
  ASSERT_EQ(json["notes"].size(), 1u);
  EXPECT_NE(json["notes"][0].get<std::string>().find("padded"), std::string::npos);
}

TEST_F(WordsCliTest, SearchComparesTakesShorterThanTheQueryWhole) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  // The whole of the longest take as a range: every other take has fewer words.
  RunResult whole_takes = RunTool("search " + archive_ + " --clip synth_000001 --top 1000 --out " +
                                  dir_->File("takes") + " --quiet");
  ASSERT_EQ(whole_takes.exit_code, 0) << whole_takes.output;
  const nlohmann::json takes = ReadJson(dir_->File("takes/search.json"));
  std::string longest = "synth_000001";
  uint64_t longest_words = takes["query"]["words"];
  uint64_t longest_frames = takes["query"]["end"];
  for (const auto& match : takes["matches"]) {  // a whole take's match: all its words' frames
    if (match["words"].get<uint64_t>() > longest_words) {
      longest = match["clip"];
      longest_words = match["words"];
      longest_frames = match["end"];
    }
  }
  RunResult range =
      RunTool("search " + archive_ + " --clip " + longest + " --start 0 --end " +
              std::to_string(longest_frames) + " --top 1000 --out " + dir_->File("long"));
  ASSERT_EQ(range.exit_code, 0) << range.output;
  const nlohmann::json json = ReadJson(dir_->File("long/search.json"));
  ASSERT_EQ(json["query"]["words"], longest_words);
  const size_t shorter = json["shorter"].size();
  EXPECT_EQ(json["shorter_takes"], shorter);
  EXPECT_GT(shorter, 0u);
  EXPECT_NE(range.output.find("  shorter      " + std::to_string(shorter) +
                              " takes of fewer words than the query's " +
                              std::to_string(longest_words) + ", each compared whole"),
            std::string::npos)
      << range.output;
  // Every shorter take is a match, once, whole; none is left out.
  EXPECT_TRUE(json["left_out"].empty());
  size_t whole = 0;
  for (const auto& match : json["matches"]) {
    if (!match["whole_take"].get<bool>()) continue;
    ++whole;
    EXPECT_EQ(match["start"], 0);
    EXPECT_EQ(match["first_word"], 0);
    EXPECT_EQ(match["rank_in_take"], 1);
    EXPECT_NE(std::find(json["shorter"].begin(), json["shorter"].end(), match["clip"]),
              json["shorter"].end());
  }
  EXPECT_EQ(whole, shorter);
}

TEST_F(WordsCliTest, ClassifyWritesItsDocumentWithAndWithoutLabels) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  RunResult plain = RunTool("classify " + archive_ + " --groups 3 --out " + dir_->File("c1"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  nlohmann::json json = ReadJson(dir_->File("c1/classify.json"));
  EXPECT_EQ(json["distance"], "emd");
  EXPECT_EQ(json["groups"], 3);
  EXPECT_FALSE(json.contains("supervised"));
  const size_t takes = json["takes"].size();
  EXPECT_GT(takes, 5u);
  EXPECT_TRUE(testing::FileExists(dir_->File("c1/classify.html")));
  // Labels: a header, a comment, two labels alternating, and a clip the archive does not have.
  {
    std::ofstream labels(dir_->File("labels.tsv"));
    labels << "clip\tlabel\n# comment\n";
    for (size_t take = 0; take < takes; ++take) {
      labels << json["takes"][take]["clip"].get<std::string>() << "\t"
             << (take % 2 ? "odd" : "even") << "\textra field\n";
    }
    labels << "not_a_clip\teven\n";
  }
  for (const char* distance : {"emd", "emd-tf", "dtw", "movement"}) {
    RunResult labelled = RunTool("classify " + archive_ + " --labels " + dir_->File("labels.tsv") +
                                 " --distance " + distance + " --out " + dir_->File(distance));
    ASSERT_EQ(labelled.exit_code, 0) << labelled.output;
    EXPECT_NE(labelled.output.find("1 labelled clips"), std::string::npos) << labelled.output;
    const nlohmann::json doc = ReadJson(dir_->File(std::string(distance) + "/classify.json"));
    EXPECT_EQ(doc["distance"], distance);
    EXPECT_EQ(doc["labels"], nlohmann::json({"even", "odd"}));
    EXPECT_EQ(doc["supervised"]["labelled"], takes);
    EXPECT_EQ(doc["takes"].size(), takes);
  }
}

// The movement distance reads the frames alone: no words files are needed (the prefix names
// none) or written, and the thread count changes nothing in the document.
TEST_F(WordsCliTest, ClassifyByMovementNeedsNoWordsFiles) {
  std::string documents[2];
  for (int threads : {1, 2}) {
    const std::string out = dir_->File("movement" + std::to_string(threads));
    RunResult run = RunTool("classify " + archive_ + " --distance movement --prefix " +
                            dir_->File("none") + " --threads " + std::to_string(threads) +
                            " --out " + out);
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_NE(run.output.find("distance movement)"), std::string::npos) << run.output;
    nlohmann::json json = ReadJson(out + "/classify.json");
    EXPECT_EQ(json["distance"], "movement");
    EXPECT_GT(json["takes"].size(), 5u);
    json.erase("seconds_distances");
    documents[threads - 1] = json.dump();
  }
  EXPECT_EQ(documents[0], documents[1]);
  // search ranks the other takes whole by the same distance, the query left out.
  const std::string out = dir_->File("movement-search");
  RunResult search = RunTool("search " + archive_ + " --clip synth_000002 --distance movement " +
                             "--top 3 --prefix " + dir_->File("none") + " --out " + out);
  ASSERT_EQ(search.exit_code, 0) << search.output;
  const nlohmann::json found = ReadJson(out + "/search.json");
  EXPECT_EQ(found["distance"], "movement");
  ASSERT_EQ(found["matches"].size(), 3u);
  for (const auto& match : found["matches"]) {
    EXPECT_NE(match["clip"], "synth_000002");
    EXPECT_TRUE(match["whole_take"].get<bool>());
  }
  EXPECT_LE(found["matches"][0]["distance"], found["matches"][1]["distance"]);
  EXPECT_FALSE(testing::FileExists(dir_->File("none.mws")));
}

TEST_F(WordsCliTest, BadInputGivesAClearErrorAndChangesNothing) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  const std::string signatures = testing::ReadBytes(dir_->File("s.mws"));
  const std::string embedding = testing::ReadBytes(dir_->File("s.mwe"));
  auto expect = [](const std::string& args, int code, const std::string& text) {
    RunResult result = RunTool(args);
    EXPECT_EQ(result.exit_code, code) << args << "\n" << result.output;
    EXPECT_NE(result.output.find(text), std::string::npos) << args << "\n" << result.output;
  };
  expect("words " + dir_->File("missing.mfs"), 11, "missing.mfs");
  expect("words " + archive_ + " --motifs 0", 2, "--motifs must be a whole number in [1, 65535]");
  expect("words " + archive_ + " --motifs 60000 --epochs 1", 13,
         "fewer than the 60000 asked for (--motifs)");
  expect("words " + archive_ + " --held-out 1", 2, "--held-out must be a number in [0, 0.9]");
  expect("classify " + archive_ + " --prefix " + dir_->File("none"), 11, "run `motifmine words`");
  expect("classify " + archive_ + " --distance cosine", 13, "--distance must be");
  {
    std::ofstream bad(dir_->File("bad.tsv"));
    bad << "synth_000001 walk\n";
  }
  expect("classify " + archive_ + " --labels " + dir_->File("bad.tsv"), 13, "bad.tsv:1:");
  expect("classify " + archive_ + " --labels " + dir_->File("nothing.tsv"), 11, "nothing.tsv");
  expect("search " + archive_, 2, "either --clip NAME or --query FILE");
  expect("search " + archive_ + " --clip synth_000001 --query x.bvh", 2, "either --clip");
  expect("search " + archive_ + " --clip synth_000001 --start 5", 2,
         "--start and --end go together");
  expect("search " + archive_ + " --clip nope", 11, "no clip named 'nope'");
  expect("search " + archive_ + " --clip synth_000001 --start 0 --end 500 --distance movement", 2,
         "--distance movement compares whole takes");
  expect("search " + archive_ + " --clip synth_000001 --distance cosine", 13,
         "--distance must be emd or movement");
  // A range shorter than one word is no longer refused: padded to one (its own test above).
  expect(
      "search " + archive_ + " --clip synth_000001 --start 10 --end 50 --out " + dir_->File("tiny"),
      0, "padded to 0.63 s by taking the word centred on it");
  expect("search " + archive_ + " --clip synth_000001 --start 10 --end 99999999", 13,
         "not a range");
  expect("search " + archive_ + " --query " + dir_->File("none.bvh"), 11, "none.bvh");
  // Refused options (other epochs included) did not retrain or rewrite anything.
  EXPECT_EQ(testing::ReadBytes(dir_->File("s.mwe")), embedding);
  EXPECT_EQ(testing::ReadBytes(dir_->File("s.mws")), signatures);
  // A damaged signatures file is refused by name, and words makes it again.
  const std::string damaged = dir_->File("s.mws");
  testing::PatchByte(damaged, 70, static_cast<char>(signatures[70] ^ 0x20));
  expect("classify " + archive_, 12, "s.mws");
  expect("search " + archive_ + " --clip synth_000001", 12, "s.mws");
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  EXPECT_EQ(testing::ReadBytes(damaged), signatures);
}

}  // namespace
}  // namespace motif

namespace motif {
namespace {

using testing::RunResult;
using testing::RunTool;

// Every take's segments cover it whole, in order, each at least one frame.
void ExpectSegmentsCoverTheTakes(const nlohmann::json& doc) {
  std::map<std::string, uint64_t> next;
  for (const nlohmann::json& segment : doc["segments"]) {
    const std::string clip = segment["clip"];
    EXPECT_EQ(segment["start"].get<uint64_t>(), next[clip]) << clip;
    EXPECT_GT(segment["end"].get<uint64_t>(), segment["start"].get<uint64_t>()) << clip;
    next[clip] = segment["end"];
  }
  for (const nlohmann::json& take : doc["takes"]) {
    EXPECT_EQ(next[take["clip"].get<std::string>()], take["frames"].get<uint64_t>());
  }
}

TEST_F(WordsCliTest, SegmentWritesItsDocumentAndPageWithAndWithoutLabels) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  RunResult plain = RunTool("segment " + archive_ + " --out " + dir_->File("seg1"));
  ASSERT_EQ(plain.exit_code, 0) << plain.output;
  const nlohmann::json doc = ReadJson(dir_->File("seg1/segments.json"));
  EXPECT_EQ(doc["mode"], "unsupervised");
  EXPECT_GT(doc["takes"].size(), 5u);
  ExpectSegmentsCoverTheTakes(doc);
  const std::string page = testing::ReadBytes(dir_->File("seg1/segments.html"));
  EXPECT_NE(page.find("class=\"timeline\""), std::string::npos);
  EXPECT_NE(page.find("<svg class=\"fig\""), std::string::npos);
  {
    std::ofstream labels(dir_->File("seg-labels.tsv"));
    labels << "clip\tlabel\n";
    for (size_t take = 0; take < doc["takes"].size(); ++take) {
      labels << doc["takes"][take]["clip"].get<std::string>() << "\t" << (take % 2 ? "b" : "a")
             << "\n";
    }
  }
  // (--distance, --signature, the signature segments.json names)
  for (const auto& [distance, signature, named] :
       {std::tuple{"emd", "", "words"}, {"emd", "motifs", "motifs"}, {"dtw", "", ""}}) {
    const std::string out = dir_->File(std::string("seg-") + distance + signature);
    RunResult labelled = RunTool(
        "segment " + archive_ + " --labels " + dir_->File("seg-labels.tsv") +
        " --clip synth_000001 --clip synth_000003 --distance " + distance +
        (*signature ? std::string(" --signature ") + signature : std::string()) + " --out " + out);
    ASSERT_EQ(labelled.exit_code, 0) << labelled.output;
    const nlohmann::json one = ReadJson(out + "/segments.json");
    EXPECT_EQ(one["mode"], "supervised");
    EXPECT_EQ(one["distance"], distance);
    if (*named) {
      EXPECT_EQ(one["signature"], named);
    } else {
      EXPECT_FALSE(one.contains("signature"));
    }
    EXPECT_EQ(one["labels"], nlohmann::json({"a", "b"}));
    ASSERT_EQ(one["takes"].size(), 2u);
    EXPECT_EQ(one["takes"][0]["clip"], "synth_000001");
    EXPECT_EQ(one["takes"][1]["clip"], "synth_000003");
    for (const nlohmann::json& segment : one["segments"]) {
      EXPECT_TRUE(segment["label"] == "a" || segment["label"] == "b") << segment.dump();
    }
    ExpectSegmentsCoverTheTakes(one);
  }
}

TEST_F(WordsCliTest, SegmentRefusesBadOptionsByNameAndWritesNothing) {
  ASSERT_EQ(RunTool("words " + archive_ + WordsArgs()).exit_code, 0);
  auto expect = [&](const std::string& args, int code, const std::string& text) {
    RunResult result = RunTool("segment " + archive_ + " --out " + dir_->File("seg-bad") + args);
    EXPECT_EQ(result.exit_code, code) << args << "\n" << result.output;
    EXPECT_NE(result.output.find(text), std::string::npos) << args << "\n" << result.output;
    EXPECT_FALSE(testing::FileExists(dir_->File("seg-bad/segments.json"))) << args;
  };
  expect(" --clip nope", 11, "no clip named 'nope'");
  expect(" --distance cosine", 13, "--distance must be emd or dtw");
  expect(" --distance dtw", 13, "--distance dtw needs --labels");
  expect(" --window 0", 2, "--window");
  expect(" --neighbours frames", 13, "--neighbours must be");
  expect(" --signature frames", 13, "--signature must be words or motifs");
  expect(" --labels x.tsv --distance dtw --signature words", 13,
         "--signature needs --distance emd");
  expect(" --labels x.tsv --groups 3", 13, "--groups is for segmenting without --labels");
  expect(" --groups 0", 2, "--groups must be auto or a whole number");
  expect(" --labels " + dir_->File("no-labels.tsv"), 11, "no-labels.tsv");
  {
    std::ofstream labels(dir_->File("elsewhere.tsv"));
    labels << "other_clip\twalk\n";
  }
  expect(" --labels " + dir_->File("elsewhere.tsv"), 13, "no labelled take");
}

// A synthetic archive of 12,000 frames in clips of 10-15 s, with no words files.
bool WriteSmallArchive(const std::string& archive) {
  return RunTool("synth " + archive + " --frames 12000 --motifs 2 --seed 5 " +
                 "--clip-seconds-min 10 --clip-seconds-max 15 --quiet")
             .exit_code == 0;
}

TEST(SegmentCli, BuildsTheWordsItNeedsWhenTheyAreMissing) {
  testing::TempDir dir;
  const std::string archive = dir.File("small.mfs");
  ASSERT_TRUE(WriteSmallArchive(archive));
  RunResult result =
      RunTool("segment " + archive + " --signature motifs --out " + dir.File("out"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("building them"), std::string::npos) << result.output;
  EXPECT_TRUE(testing::FileExists(dir.File("small.mws")));
  ExpectSegmentsCoverTheTakes(ReadJson(dir.File("out/segments.json")));
  // A second run reads them back instead.
  RunResult again =
      RunTool("segment " + archive + " --signature motifs --out " + dir.File("out"));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(again.output.find("building them"), std::string::npos) << again.output;
}

// Word signatures (the supervised default) and the DTW baseline need only where the words lie:
// no words files are built for them, and the result is the one made with the files present.
TEST(SegmentCli, WordSignaturesNeedNoWordsFiles) {
  testing::TempDir dir;
  const std::string archive = dir.File("small.mfs");
  ASSERT_TRUE(WriteSmallArchive(archive));
  {
    std::ofstream labels(dir.File("labels.tsv"));
    labels << "synth_000000\ta\nsynth_000001\tb\nsynth_000002\ta\nsynth_000003\tb\n";
  }
  const std::string args = " --labels " + dir.File("labels.tsv") + " --clip synth_000004";
  RunResult result = RunTool("segment " + archive + args + " --out " + dir.File("grid"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("no embedding is needed"), std::string::npos) << result.output;
  EXPECT_FALSE(testing::FileExists(dir.File("small.mws")));
  EXPECT_FALSE(testing::FileExists(dir.File("small.mwe")));
  RunResult dtw =
      RunTool("segment " + archive + args + " --distance dtw --out " + dir.File("grid-dtw"));
  ASSERT_EQ(dtw.exit_code, 0) << dtw.output;
  EXPECT_FALSE(testing::FileExists(dir.File("small.mws")));
  ASSERT_EQ(RunTool("words " + archive + " --epochs 1 --channels 16 --dims 8 --motifs 8 --quiet")
                .exit_code,
            0);
  RunResult with_files = RunTool("segment " + archive + args + " --out " + dir.File("files"));
  ASSERT_EQ(with_files.exit_code, 0) << with_files.output;
  EXPECT_EQ(ReadJson(dir.File("grid/segments.json"))["segments"],
            ReadJson(dir.File("files/segments.json"))["segments"]);
}

// Unsupervised segmentation by affinity profiles (the default) reads no embedding: no words files
// are built, and words files of any seed give the same segments and groups. Each group lists its
// member stretches, which are the segments carrying its label; --groups K gives K groups.
TEST(SegmentCli, UnsupervisedSegmentsDependOnNoSeedAndListEachGroupsMembers) {
  testing::TempDir dir;
  const std::string archive = dir.File("small.mfs");
  ASSERT_TRUE(WriteSmallArchive(archive));
  RunResult grid = RunTool("segment " + archive + " --out " + dir.File("grid"));
  ASSERT_EQ(grid.exit_code, 0) << grid.output;
  EXPECT_FALSE(testing::FileExists(dir.File("small.mws")));
  const nlohmann::json plain = ReadJson(dir.File("grid/segments.json"));
  EXPECT_EQ(plain["signature"], "words");
  EXPECT_EQ(plain["linkage"], "average");
  for (const char* seed : {"1", "2"}) {
    const std::string prefix = dir.File(std::string("seed") + seed);
    ASSERT_EQ(RunTool("words " + archive + " --epochs 1 --channels 16 --dims 8 --motifs 8 " +
                      "--quiet --seed " + seed + " --prefix " + prefix)
                  .exit_code,
              0);
    const std::string out = dir.File(std::string("out") + seed);
    ASSERT_EQ(RunTool("segment " + archive + " --prefix " + prefix + " --out " + out).exit_code,
              0);
    const nlohmann::json again = ReadJson(out + "/segments.json");
    EXPECT_EQ(again["segments"], plain["segments"]) << "seed " << seed;
    EXPECT_EQ(again["groups"], plain["groups"]) << "seed " << seed;
  }
  ASSERT_EQ(plain["groups"].size(), plain["labels"].size());
  size_t members = 0;
  for (const nlohmann::json& group : plain["groups"]) {
    for (const nlohmann::json& member : group["members"]) {
      const bool listed = std::any_of(
          plain["segments"].begin(), plain["segments"].end(), [&](const nlohmann::json& segment) {
            return segment["clip"] == member["clip"] && segment["start"] == member["start"] &&
                   segment["end"] == member["end"] && segment["label"] == group["label"];
          });
      EXPECT_TRUE(listed) << member.dump();
      ++members;
    }
  }
  EXPECT_EQ(members, plain["segments"].size());
  ASSERT_EQ(RunTool("segment " + archive + " --groups 2 --out " + dir.File("two")).exit_code, 0);
  const nlohmann::json two = ReadJson(dir.File("two/segments.json"));
  EXPECT_EQ(two["labels"].size(), 2u);
  // The cuts do not move; neighbouring segments that now share a group merge.
  EXPECT_LE(two["segments"].size(), plain["segments"].size());
}

// On a real exercise routine (13_31 of ../shared/data/mocap6: Twist, KneeRaise, ToeTouchOneHand,
// Twist again, Jog, ArmCircle, JumpJack), the two Twist stretches share a group and the five other
// exercises each have a group of their own.
TEST(SegmentCli, TheTwoTwistsOfARealRoutineShareAGroupAndNoOtherExerciseDoes) {
  MOTIF_REQUIRE_EXERCISE_ROUTINES();
  const std::string data = testing::ExerciseRoutinesDir();
  testing::TempDir dir;
  const std::string archive = dir.File("routine.mfs");
  ASSERT_EQ(RunTool("import " + archive + " " + data + "/13_31.amc --asf " + data +
                    "/13.asf --quiet")
                .exit_code,
            0);
  ASSERT_EQ(RunTool("segment " + archive + " --quiet --out " + dir.File("out")).exit_code, 0);
  const nlohmann::json doc = ReadJson(dir.File("out/segments.json"));
  const auto label_at = [&](uint64_t frame) {
    for (const nlohmann::json& segment : doc["segments"]) {
      if (segment["start"].get<uint64_t>() <= frame && frame < segment["end"].get<uint64_t>()) {
        return segment["label"].get<std::string>();
      }
    }
    return std::string("none");
  };
  // A frame well inside each annotated stretch (mocap6's labels: Twist 0-396 and 1392-1608,
  // KneeRaise 396-984, ToeTouchOneHand -1392, Jog -2052, ArmCircle -2724, JumpJack -3017).
  EXPECT_EQ(label_at(100), label_at(1500));
  std::set<std::string> labels{label_at(100)};
  for (uint64_t frame : {700, 1200, 1850, 2400, 2900}) labels.insert(label_at(frame));
  EXPECT_EQ(labels.size(), 6u) << doc["segments"].dump();
  EXPECT_LE(doc["labels"].size(), 9u) << "at most 1.5 groups per exercise";
}

}  // namespace
}  // namespace motif
