// report.html in a real browser: headless Chromium loads the report of a small synthetic archive
// (motifs.json written by hand from its planted instances; one motif drawn in the file, the
// others by the page's script), clicks "Draw all figures", and the page must have run without a
// script error and hold every motif section and every stick figure. A screenshot is saved under
// the test's working directory (the build tree) and its path printed, for a person to look at.
//
// The report is checked through an instrumented copy (tests/testing/headless_chromium.h): after
// load, a last script clicks the button and writes what it counted. Chromium's console log is
// searched for "Uncaught" as well. Skips when no Chromium is installed.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "engine/cluster/motifs_json.h"
#include "engine/synth/truth_json_reader.h"
#include "formats/frame_file/frame_file_reader.h"
#include "tests/testing/headless_chromium.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

using testing::RunResult;
using testing::RunShell;
using testing::RunTool;

constexpr char kTailScript[] =
    "<script>window.addEventListener('load',function(){"
    "var b=document.getElementById('draw-all');if(b)b.click();"
    "window.scrollTo(0,document.body.scrollHeight);"
    "setTimeout(function(){var f=document.querySelectorAll('.figs svg.fig'),drawn=0;"
    "for(var i=0;i<f.length;i++){var p=f[i].querySelector('path');"
    "if(p&&(p.getAttribute('d')||'').length>20)++drawn;}"
    "var m=document.createElement('pre');m.id='e2e-result';m.hidden=true;"
    "m.textContent=JSON.stringify({errors:window.__e2eErrors,"
    "button:!!b,"
    "motifs:document.querySelectorAll('section.motif').length,"
    "figures:f.length,drawn:drawn,"
    "timeline:document.querySelectorAll('.tl rect').length});"
    "document.body.appendChild(m);window.scrollTo(0,0);},300);});</script>";

TEST(ReportBrowser, RendersEveryFigureWithoutScriptErrors) {
  const std::string chromium = testing::FindChromium();
  if (chromium.empty()) {
    GTEST_SKIP() << "no Chromium found (apt-get install chromium, or set MOTIF_CHROMIUM): "
                    "report.html is not checked in a browser";
  }
  testing::TempDir dir;
  const std::string archive = dir.File("s.mfs");
  RunResult synth =
      RunTool("synth " + archive + " --frames 9000 --motifs 3 --seed 5 " +
              "--motif-seconds-max 1.5 --clip-seconds-min 10 " + "--clip-seconds-max 20 --quiet");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  auto truth = ReadTruthJson(dir.File("s.truth.json"));
  ASSERT_TRUE(truth.ok()) << truth.status().ToString();
  auto reader = FrameFileReader::Open(archive);
  ASSERT_TRUE(reader.ok());

  MotifsDocument document;
  document.archive = archive;
  document.frames = (*reader)->frame_count();
  std::map<std::string, uint64_t> first_frames;
  for (const ClipInfo& clip : (*reader)->clips()) {
    document.clips.push_back(
        {clip.name, clip.source_path, clip.frame_count, clip.fps, clip.first_frame});
    first_frames[clip.name] = clip.first_frame;
  }
  document.params = {1.0, 64, 4, 60, 0, 1};
  std::map<uint32_t, std::vector<MotifsJsonInstance>> by_motif;
  for (const PlantedInstance& planted : truth->instances) {
    by_motif[planted.motif].push_back(
        {planted.clip, planted.start, planted.end, first_frames[planted.clip] + planted.start});
  }
  for (auto& [motif_id, instances] : by_motif) document.motifs.push_back({motif_id, instances});
  ASSERT_GE(document.motifs.size(), 3u);
  std::filesystem::create_directories(dir.File("out"));
  ASSERT_TRUE(WriteMotifsJson(dir.File("out/motifs.json"), document).ok());

  // Motif 0's figures are in the file, the others are drawn by the script.
  constexpr size_t kKeyframes = 5, kInstancesDrawn = 4;
  RunResult report = RunTool(
      "report " + dir.File("out") + " --eager 1 --keyframes " + std::to_string(kKeyframes) +
      " --instances " + std::to_string(kInstancesDrawn) + " --truth " + dir.File("s.truth.json"));
  ASSERT_EQ(report.exit_code, 0) << report.output;
  size_t expected_figures = 0, instances = 0;
  for (const MotifsJsonMotif& motif : document.motifs) {
    expected_figures += std::min(motif.instances.size(), kInstancesDrawn) * kKeyframes;
    instances += motif.instances.size();
  }

  auto html = ReadFileToString(dir.File("out/report.html"));
  ASSERT_TRUE(html.ok());
  const std::string instrumented = dir.File("out/report.e2e.html");
  const testing::InstrumentedRun run =
      testing::RunInstrumentedPage(chromium, *html, kTailScript, instrumented, dir.path());
  ASSERT_TRUE(run.error.empty()) << run.error;
  const nlohmann::json& result = run.result;
  EXPECT_TRUE(result["errors"].empty()) << result["errors"].dump(2);
  EXPECT_EQ(run.log.find("Uncaught"), std::string::npos) << run.log;
  EXPECT_TRUE(result["button"].get<bool>()) << "no Draw all figures button";
  EXPECT_EQ(result["motifs"].get<size_t>(), document.motifs.size());
  EXPECT_EQ(result["figures"].get<size_t>(), expected_figures);
  EXPECT_EQ(result["drawn"].get<size_t>(), expected_figures) << "figures with an empty path";
  EXPECT_EQ(result["timeline"].get<size_t>(), instances);

  // The screenshot, kept in the build tree (the test's working directory) for a person to see.
  const std::filesystem::path artefacts =
      std::filesystem::absolute("report_browser_test_artefacts");
  std::filesystem::create_directories(artefacts);
  const std::string png = (artefacts / "report.png").string();
  std::filesystem::remove(png);
  RunResult shot =
      RunShell("timeout 180 " + testing::ChromiumCommand(chromium, dir.File("profile2")) +
               "--window-size=1200,3000 --screenshot='" + png + "' 'file://" + instrumented +
               "' >/dev/null 2>&1");
  ASSERT_EQ(shot.exit_code, 0);
  std::filesystem::copy_file(instrumented, artefacts / "report.e2e.html",
                             std::filesystem::copy_options::overwrite_existing);
  auto bytes = ReadFileToString(png);
  ASSERT_TRUE(bytes.ok()) << "no screenshot written";
  ASSERT_GT(bytes->size(), 24u);
  EXPECT_EQ(bytes->substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  const auto be32 = [&](size_t at) {
    return (static_cast<uint32_t>(static_cast<unsigned char>((*bytes)[at])) << 24) |
           (static_cast<uint32_t>(static_cast<unsigned char>((*bytes)[at + 1])) << 16) |
           (static_cast<uint32_t>(static_cast<unsigned char>((*bytes)[at + 2])) << 8) |
           static_cast<uint32_t>(static_cast<unsigned char>((*bytes)[at + 3]));
  };
  EXPECT_EQ(be32(16), 1200u);  // IHDR width
  EXPECT_EQ(be32(20), 3000u);  // IHDR height
  std::cout << "[ artefact ] screenshot of report.html (" << document.motifs.size() << " motifs, "
            << expected_figures << " figures): " << png << "\n";
}

}  // namespace
}  // namespace motif
