#include "engine/report/report_html.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <regex>
#include <set>

#include "common/file_util.h"
#include "engine/report/forward_kinematics.h"
#include "engine/report/instance_playback.h"
#include "tests/engine/report/report_test_util.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

size_t CountOf(const std::string& text, const std::string& needle) {
  size_t count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

// Checks that every element is closed in order (void elements and "/>" aside) and that script
// and style bodies are skipped; returns the first problem, or "".
std::string CheckTagBalance(const std::string& html) {
  static const std::set<std::string> kVoid = {"meta", "br", "hr", "img", "input", "link"};
  std::vector<std::string> open;
  size_t at = 0;
  while ((at = html.find('<', at)) != std::string::npos) {
    if (html.compare(at, 9, "<!DOCTYPE") == 0) {
      at = html.find('>', at);
      continue;
    }
    const size_t close = html.find('>', at);
    if (close == std::string::npos) return "unterminated tag at " + std::to_string(at);
    const std::string tag = html.substr(at + 1, close - at - 1);
    at = close + 1;
    if (tag.empty()) return "empty tag";
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name) {
        return "</" + name + "> closes <" + (open.empty() ? "" : open.back()) + ">";
      }
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \n"));
    if (tag.back() == '/' || kVoid.count(name)) continue;
    if (name == "script" || name == "style") {
      const size_t end = html.find("</" + name + ">", at);
      if (end == std::string::npos) return "unclosed " + name;
      at = end + name.size() + 3;
      continue;
    }
    open.push_back(name);
  }
  return open.empty() ? "" : "unclosed <" + open.back() + ">";
}

// The script's decoding of EncodeFigurePoints, in C++: the SVG it would draw.
std::string DecodeFigure(const std::string& encoded, size_t offset,
                         const StickFigureLayout& layout) {
  static const std::string kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
  std::vector<FigurePoint> points(layout.points.size());
  for (size_t point_idx = 0; point_idx < points.size(); ++point_idx) {
    for (int axis = 0; axis < 2; ++axis) {
      const size_t at = offset + 4 * point_idx + 2 * axis;
      const long code =
          static_cast<long>(kAlphabet.find(encoded[at]) * 64 + kAlphabet.find(encoded[at + 1]));
      points[point_idx][axis] = (code - 1000) / 10.0;
    }
  }
  return StickFigureSvg(layout, points, kFigureWidthPx, kFigureHeightPx);
}

class ReportHtmlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SynthOptions options;
    options.frames = 12000;
    options.motifs = 3;
    options.seed = 11;
    options.clip_seconds_min = 10;
    options.clip_seconds_max = 20;
    options.motif_seconds_max = 1.5;
    options.threads = 1;
    auto made = testing::MakeSyntheticMotifs(dir_.File("a.mfs"), options, kOddName);
    ASSERT_TRUE(made.ok()) << made.status().ToString();
    synthetic_ = std::move(made).value();
    auto reader = FrameFileReader::Open(synthetic_.archive_path);
    ASSERT_TRUE(reader.ok()) << reader.status().ToString();
    reader_ = std::move(reader).value();
    for (const MotifsJsonMotif& motif : synthetic_.document.motifs) {
      instances_ += motif.instances.size();
    }
    bool odd_name_used = false;
    for (const PlantedInstance& instance : synthetic_.truth)
      odd_name_used |= instance.clip == kOddName;
    ASSERT_TRUE(odd_name_used) << "the renamed clip should hold an instance";
  }

  static constexpr char kOddName[] = "take<&\">'1";
  testing::TempDir dir_;
  testing::SyntheticMotifs synthetic_;
  std::unique_ptr<FrameFileReader> reader_;
  size_t instances_ = 0;
};

TEST_F(ReportHtmlTest, WritesASelfContainedWellFormedPage) {
  ReportInfo info;
  info.parameters_text = "motifmine mine a.mfs --eps auto";
  info.timings = {{"trellis", 1.5}, {"grow", 0.25}};
  info.peak_memory_bytes = 300ull << 20;
  const std::string path = dir_.File("report.html");
  ASSERT_TRUE(WriteReportHtml(path, synthetic_.document, *reader_, info).ok());
  auto read = ReadFileToString(path);
  ASSERT_TRUE(read.ok());
  const std::string& html = *read;

  EXPECT_EQ(CheckTagBalance(html), "");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(CountOf(html, "<rect"), instances_) << "one timeline rectangle per instance";
  EXPECT_EQ(CountOf(html, "<section class=\"motif\""), synthetic_.document.motifs.size());
  for (const MotifsJsonMotif& motif : synthetic_.document.motifs) {
    EXPECT_EQ(CountOf(html, "id=\"m" + std::to_string(motif.id) + "\""), 1u);
  }
  // Nothing is fetched: no URL, no external source, every link points inside the page.
  EXPECT_EQ(html.find("http"), std::string::npos);
  EXPECT_EQ(html.find("src="), std::string::npos);
  EXPECT_EQ(html.find("url("), std::string::npos);
  EXPECT_EQ(html.find("@import"), std::string::npos);
  const std::regex href("href=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), href); it != std::sregex_iterator();
       ++it) {
    EXPECT_EQ((*it)[1].str()[0], '#') << (*it)[0];
  }
  // All motifs are eager here: 3 motifs x up to 4 instances x 5 keyframes.
  size_t drawn = 0;
  for (const MotifsJsonMotif& motif : synthetic_.document.motifs) {
    drawn += std::min<size_t>(motif.instances.size(), 4) * 5;
  }
  const std::string page = html.substr(0, html.find("<script"));  // the script builds SVG too
  EXPECT_EQ(CountOf(page, "<svg class=\"fig\""), drawn);
  EXPECT_EQ(html.find("id=\"pose-data\""), std::string::npos);
  // Overview.
  EXPECT_NE(html.find("trellis</td><td>1.50 s"), std::string::npos);
  EXPECT_NE(html.find("300.0 MiB"), std::string::npos);
  EXPECT_NE(html.find(std::to_string(instances_) + " instances"), std::string::npos);
  EXPECT_NE(html.find("motifmine mine a.mfs --eps auto"), std::string::npos);
}

TEST_F(ReportHtmlTest, EscapesClipNames) {
  auto html = ReportHtmlText(synthetic_.document, *reader_, {});
  ASSERT_TRUE(html.ok()) << html.status().ToString();
  EXPECT_EQ(html->find(kOddName), std::string::npos);
  EXPECT_NE(html->find("take&lt;&amp;&quot;&gt;&#39;1"), std::string::npos);
  // In the player's JSON the name is a JSON string whose '<' cannot end its script block.
  EXPECT_NE(html->find(R"("clip":"take\u003c&\">'1")"), std::string::npos);
  EXPECT_EQ(CheckTagBalance(*html), "");
  EXPECT_EQ(HtmlEscape("<a href=\"x\">&'"), "&lt;a href=&quot;x&quot;&gt;&amp;&#39;");
}

TEST_F(ReportHtmlTest, LazyFiguresDecodeToTheEagerOnes) {
  ReportOptions eager_options;
  ReportOptions lazy_options;
  lazy_options.eager_motifs = 1;
  auto eager = ReportHtmlText(synthetic_.document, *reader_, {}, eager_options);
  auto lazy = ReportHtmlText(synthetic_.document, *reader_, {}, lazy_options);
  ASSERT_TRUE(eager.ok() && lazy.ok());
  EXPECT_EQ(CheckTagBalance(*lazy), "");
  EXPECT_LT(lazy->size(), eager->size());
  EXPECT_EQ(CountOf(*lazy, "data-m=\""), synthetic_.document.motifs.size() - 1);
  EXPECT_NE(lazy->find("<script type=\"application/json\" id=\"pose-data\">"), std::string::npos);
  EXPECT_NE(lazy->find("IntersectionObserver"), std::string::npos);

  // The eager figures in page order, and each lazy motif's strings decoded the script's way.
  const std::regex figure("<svg class=\"fig\"[^]*?</svg>");
  std::vector<std::string> eager_figures;
  const std::string eager_page = eager->substr(0, eager->find("<script"));
  for (auto it = std::sregex_iterator(eager_page.begin(), eager_page.end(), figure);
       it != std::sregex_iterator(); ++it) {
    eager_figures.push_back((*it)[0]);
  }
  const StickFigureLayout layout = MakeStickFigureLayout(reader_->skeleton());
  const std::regex strings("\"([A-Za-z0-9_-]{40,})\"");
  std::vector<std::string> decoded;
  for (auto it = std::sregex_iterator(lazy->begin(), lazy->end(), strings);
       it != std::sregex_iterator(); ++it) {
    const std::string encoded = (*it)[1];
    ASSERT_EQ(encoded.size() % (4 * layout.points.size()), 0u);
    for (size_t offset = 0; offset < encoded.size(); offset += 4 * layout.points.size()) {
      decoded.push_back(DecodeFigure(encoded, offset, layout));
    }
  }
  const size_t first_motif_figures =
      std::min<size_t>(synthetic_.document.motifs[0].instances.size(), 4) * 5;
  ASSERT_EQ(decoded.size() + first_motif_figures, eager_figures.size());
  for (size_t idx = 0; idx < decoded.size(); ++idx) {
    EXPECT_EQ(decoded[idx], eager_figures[first_motif_figures + idx]) << "figure " << idx;
  }
}

TEST_F(ReportHtmlTest, RefusesMotifsOfAnotherArchive) {
  MotifsDocument other = synthetic_.document;
  other.frames += 1;
  EXPECT_TRUE(ReportHtmlText(other, *reader_, {}).status().IsInvalidArgument());
  other = synthetic_.document;
  other.motifs[0].instances[0].end = 1u << 30;
  EXPECT_TRUE(ReportHtmlText(other, *reader_, {}).status().IsInvalidArgument());
}

TEST_F(ReportHtmlTest, EmptyDocumentStillRenders) {
  MotifsDocument empty = synthetic_.document;
  empty.motifs.clear();
  auto html = ReportHtmlText(empty, *reader_, {});
  ASSERT_TRUE(html.ok());
  EXPECT_NE(html->find("No motifs were found."), std::string::npos);
  EXPECT_EQ(CountOf(*html, "<rect"), 0u);
  EXPECT_EQ(CheckTagBalance(*html), "");
}

// Every motif gets a player with every instance's samples; over the budget, a note instead.
TEST_F(ReportHtmlTest, EveryMotifHasAPlayerOfAllItsInstances) {
  auto html = ReportHtmlText(synthetic_.document, *reader_, {});
  ASSERT_TRUE(html.ok()) << html.status().ToString();
  EXPECT_EQ(CountOf(*html, "<button type=\"button\" class=\"play\""),
            synthetic_.document.motifs.size());
  EXPECT_EQ(CountOf(*html, "id=\"play-figure\""), 1u);
  for (const MotifsJsonMotif& motif : synthetic_.document.motifs) {
    const std::string id = std::to_string(motif.id);
    const size_t block = html->find("<script type=\"application/json\" id=\"play-" + id + "\">");
    ASSERT_NE(block, std::string::npos) << "motif " << id;
    const size_t begin = html->find('>', block) + 1;
    const nlohmann::json data =
        nlohmann::json::parse(html->substr(begin, html->find("</script>", begin) - begin));
    ASSERT_EQ(data["instances"].size(), motif.instances.size());
    for (size_t idx = 0; idx < motif.instances.size(); ++idx) {
      const nlohmann::json& instance = data["instances"][idx];
      EXPECT_EQ(instance["clip"].get<std::string>(), motif.instances[idx].clip);
      EXPECT_EQ(instance["start"].get<uint64_t>(), motif.instances[idx].start);
      EXPECT_EQ(instance["end"].get<uint64_t>(), motif.instances[idx].end);
    }
  }
  ReportOptions tiny;
  tiny.playback_bytes = 1;
  auto without = ReportHtmlText(synthetic_.document, *reader_, {}, tiny);
  ASSERT_TRUE(without.ok());
  EXPECT_EQ(CountOf(*without, "class=\"play\""), 0u);
  EXPECT_EQ(CountOf(*without, "Playback of this motif is not in the page"),
            synthetic_.document.motifs.size());
}

// Figure k of every strip is the moment the player shows with the first instance's keyframe
// sample k: the strips' frames are start + align[key] x step of the player's own alignment; the
// player's figure carries the strips' colour table.
TEST_F(ReportHtmlTest, StripKeyframesAreThePlayersAlignedMoments) {
  auto html = ReportHtmlText(synthetic_.document, *reader_, {});
  ASSERT_TRUE(html.ok()) << html.status().ToString();
  EXPECT_NE(html->find(R"("colours":["#555","#1f6fd1","#d62728")"), std::string::npos);
  const uint32_t step = PlaybackStep(reader_->fps());
  size_t strips = 0;
  size_t warped_strips = 0;  // strips whose frames differ from even spacing
  for (const MotifsJsonMotif& motif : synthetic_.document.motifs) {
    const std::string id = std::to_string(motif.id);
    const size_t block = html->find("<script type=\"application/json\" id=\"play-" + id + "\"");
    ASSERT_NE(block, std::string::npos);
    const size_t begin = html->find('>', block) + 1;
    const nlohmann::json data =
        nlohmann::json::parse(html->substr(begin, html->find("</script>", begin) - begin));
    const uint32_t reference_samples = data["instances"][0]["samples"];
    // This motif's section: each strip's label says its instance's frames and the keyframes'.
    const size_t section = html->find("<section class=\"motif\" id=\"m" + id + "\"");
    const std::string motif_html =
        html->substr(section, html->find("</section>", section) - section);
    const std::regex label(
        " ([0-9]+)\u2013([0-9]+) \\([^)]*\\)<br><span class=\"kf\">frames ([^<]*)<");
    for (auto it = std::sregex_iterator(motif_html.begin(), motif_html.end(), label);
         it != std::sregex_iterator(); ++it, ++strips) {
      const uint64_t start = std::stoull((*it)[1]);
      const uint64_t end = std::stoull((*it)[2]);
      const nlohmann::json* instance = nullptr;
      for (const nlohmann::json& candidate : data["instances"]) {
        if (candidate["start"] == start && candidate["end"] == end) instance = &candidate;
      }
      ASSERT_NE(instance, nullptr) << "motif " << id << " [" << start << ", " << end << ")";
      const std::vector<uint32_t> align = (*instance)["align"];
      std::string expected;
      std::string even;
      for (uint32_t key = 0; key < 5; ++key) {
        const auto sample =
            static_cast<uint32_t>(std::llround(key * (reference_samples - 1.0) / 4));
        expected +=
            (key ? " \u00b7 " : "") + std::to_string(start + uint64_t{align[sample]} * step);
        even += (key ? " \u00b7 " : "") +
                std::to_string(start + std::llround(key * (end - start - 1.0) / 4));
      }
      EXPECT_EQ((*it)[3].str(), expected) << "motif " << id << " [" << start << ", " << end << ")";
      warped_strips += (*it)[3].str() != even;
    }
  }
  size_t drawn = 0;
  for (const MotifsJsonMotif& motif : synthetic_.document.motifs) {
    drawn += std::min<size_t>(motif.instances.size(), 4);
  }
  EXPECT_EQ(strips, drawn);
  EXPECT_GT(warped_strips, 0u) << "some instance should not be a linear stretch of the first";
}

// The overview's counts are singular or plural as they should be; the parameters are named
// once, in words with the symbols beside them; the timeline has a time axis.
TEST_F(ReportHtmlTest, OverviewSaysOneClipAndNamesParametersOnce) {
  MotifsDocument one = synthetic_.document;
  one.motifs.resize(1);
  auto html = ReportHtmlText(one, *reader_, {});
  ASSERT_TRUE(html.ok());
  EXPECT_NE(html->find(">1 motif, "), std::string::npos);
  EXPECT_EQ(html->find("1 motifs"), std::string::npos);
  EXPECT_NE(html->find("match radius &epsilon; "), std::string::npos);
  EXPECT_EQ(CountOf(*html, "&epsilon;"), 1u);
  EXPECT_NE(html->find("shortest motif &lambda; "), std::string::npos);
  EXPECT_NE(html->find("class=\"axis\"><span style=\"left:0.00%\">0 s</span>"), std::string::npos);
  EXPECT_NE(html->find("<span class=\"kf\">frames "), std::string::npos);
}

// 1,000 motifs of 3 to 8 instances (random, overlapping: only the size and the time matter):
// the page must stay small. Prints the size for the record.
TEST_F(ReportHtmlTest, ThousandMotifsStaySmall) {
  MotifsDocument large = synthetic_.document;
  large.motifs.clear();
  std::mt19937_64 rng(3);
  size_t instance_count = 0;
  for (uint32_t motif_id = 0; motif_id < 1000; ++motif_id) {
    MotifsJsonMotif motif;
    motif.id = motif_id;
    const size_t count = 3 + rng() % 6;
    for (size_t idx = 0; idx < count; ++idx) {
      const MotifsJsonClip& clip = large.clips[rng() % large.clips.size()];
      const uint64_t length = 60 + rng() % 300;
      if (clip.frames <= length) continue;
      const uint64_t start = rng() % (clip.frames - length);
      motif.instances.push_back({clip.name, start, start + length, clip.first_frame + start});
    }
    if (motif.instances.empty()) continue;
    instance_count += motif.instances.size();
    large.motifs.push_back(motif);
  }
  // Without the player's data first: the page itself.
  ReportOptions no_playback;
  no_playback.playback_bytes = 0;
  auto page = ReportHtmlText(large, *reader_, {}, no_playback);
  ASSERT_TRUE(page.ok()) << page.status().ToString();
  EXPECT_LT(page->size(), 5u * 1000 * 1000);
  EXPECT_EQ(CountOf(*page, "class=\"play\""), 0u);
  EXPECT_EQ(CountOf(*page, "No player in this page"), large.motifs.size());

  const auto started = std::chrono::steady_clock::now();
  auto html = ReportHtmlText(large, *reader_, {});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  ASSERT_TRUE(html.ok()) << html.status().ToString();
  std::printf("report of %zu motifs, %zu instances: %zu bytes (%.2f MB), %.2f s\n",
              large.motifs.size(), instance_count, html->size(), html->size() / 1e6, seconds);
  // MOTIF_REPORT_DUMP=FILE keeps the page, to look at it or measure its parts.
  if (const char* dump = std::getenv("MOTIF_REPORT_DUMP")) {
    const Status dumped = AtomicWriteFile(dump, *html);
    EXPECT_TRUE(dumped.ok()) << dumped.ToString();
  }
  // The player's data stays within its budget (base64 plus a little JSON per instance).
  const ReportOptions defaults;
  EXPECT_LT(html->size(), 5u * 1000 * 1000 + defaults.playback_bytes * 21 / 20);
  EXPECT_GT(CountOf(*html, "class=\"play\""), 0u);
  EXPECT_EQ(CountOf(*html, "class=\"play\"") + CountOf(*html, "Playback of this motif is not"),
            large.motifs.size());
  EXPECT_EQ(CountOf(*html, "<rect"), instance_count);
  EXPECT_EQ(CheckTagBalance(*html), "");
}

}  // namespace
}  // namespace motif
