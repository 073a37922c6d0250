// report.html's player in a real browser, on a real take: `motifmine mine` on a CMU take in which
// a person repeats a movement writes report.html; headless Chromium opens the first motif's
// player, which must show every instance of that motif side by side, then drives it through
// the page's own controls: play (the frame advances), pause, scrub to a frame, switch instance.
// After each scrub the pose the player holds must be the archive's frame (forward kinematics of
// the same clip frame, to within the int16 quantisation) and its bones must be painted on the
// canvas. Skips when the real takes or Chromium are absent. Saves a screenshot of the player
// under the build tree for a person to look at.

#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include <gtest/gtest.h>

#include "common/file_util.h"
#include "engine/cluster/motifs_json.h"
#include "engine/report/forward_kinematics.h"
#include "engine/report/instance_playback.h"
#include "engine/report/stick_figure_svg.h"
#include "formats/frame_file/frame_file_reader.h"
#include "formats/motion/pose_frames.h"
#include "tests/testing/headless_chromium.h"
#include "tests/testing/mocap_data.h"
#include "tests/testing/run_tool.h"
#include "tests/testing/temp_dir.h"

namespace motif {
namespace {

// Opens the first motif's player and drives it; writes what it saw into <pre id="e2e-result">.
constexpr char kPlayerScript[] = R"js(<script>window.addEventListener('load',function(){
var out={},sec=document.querySelector('section.motif'),b=sec&&sec.querySelector('button.play');
out.button=!!b;if(!b)return done();
b.click();var id=b.getAttribute('data-play'),P=window.motifPlayers&&window.motifPlayers[id];
out.player=!!P;if(!P)return done();
var ui=sec.querySelector('.player'),F=JSON.parse(document.getElementById('play-figure').textContent);
out.cells=ui.querySelectorAll('.psmall canvas').length;
out.start_frame=P.state().frame;
ui.querySelector('button.pp').click();
// Animation frames come when the (virtual) clock lets them: wait until the frame moves, 3 s at most.
var polls=0;function poll(){var s=P.state();if(s.frame==out.start_frame&&++polls<30)return setTimeout(poll,100);
out.played={frame:s.frame,playing:s.playing,polls:polls};
ui.querySelector('button.pp').click();out.paused=!P.state().playing;
var sc=ui.querySelector('input.scrub');sc.value=Math.floor(sc.max/2);sc.dispatchEvent(new Event('input'));
out.scrub=sample(+sc.value);
var is=ui.querySelector('select.inst');if(is.options.length>1){is.value='1';is.dispatchEvent(new Event('change'));}
sc.value=Math.floor(sc.max/3);sc.dispatchEvent(new Event('input'));
out.switched=sample(+sc.value);ui.scrollIntoView();done();}
setTimeout(poll,100);
function sample(k){var s=P.state(),g=s.canvas.getContext('2d'),bones=0,painted=0;
for(var c=0;c<F.chains.length;c++){var ch=F.chains[c];for(var j=1;j<ch.length;j++){
var a=s.drawn[ch[j-1]],e=s.drawn[ch[j]];if(Math.hypot(a[0]-e[0],a[1]-e[1])<4)continue;++bones;
var px=g.getImageData(Math.round((a[0]+e[0])/2),Math.round((a[1]+e[1])/2),1,1).data;
if(Math.min(px[0],px[1],px[2])<200)++painted;}}
return{scrub:k,instance:s.instance,clip:s.clip,frame:s.frame,label:s.label,points:s.points,bones:bones,painted:painted};}
function done(){out.errors=window.__e2eErrors;var m=document.createElement('pre');m.id='e2e-result';
m.hidden=true;m.textContent=JSON.stringify(out);document.body.appendChild(m);}
});</script>)js";

// The archive's pose at clip frame `frame` of `instance`, as the player encodes it: forward
// kinematics of the instance's frames from its start, the layout's points.
std::vector<Eigen::Vector3d> ArchivePose(const FrameFileReader& reader, const ClipInfo& clip,
                                         uint64_t start, uint64_t frame) {
  std::vector<float> rows;
  EXPECT_TRUE(reader.ReadFrames(clip.first_frame + start, frame - start + 1, &rows).ok());
  const Take take = ClipFramesToTake(reader.skeleton(), clip, rows.data(), frame - start + 1);
  const std::vector<Eigen::Vector3d> pose = TakeFramePositions(take, frame - start);
  std::vector<Eigen::Vector3d> points;
  for (uint32_t point : MakeStickFigureLayout(reader.skeleton()).points) {
    points.push_back(pose[point]);
  }
  return points;
}

void ExpectArchivePose(const nlohmann::json& seen, const MotifsDocument& document,
                       const FrameFileReader& reader, uint32_t step) {
  const MotifsJsonInstance& instance =
      document.motifs[0].instances.at(seen["instance"].get<size_t>());
  EXPECT_EQ(seen["clip"].get<std::string>(), instance.clip);
  // The scrubber moves over the instance's samples: sample k is clip frame start + k * step.
  const uint64_t frame = seen["frame"].get<uint64_t>();
  EXPECT_EQ(frame, instance.start + seen["scrub"].get<uint64_t>() * step);
  const ClipInfo* clip = nullptr;
  for (const ClipInfo& info : reader.clips()) {
    if (info.name == instance.clip) clip = &info;
  }
  ASSERT_NE(clip, nullptr);
  // The label names both frames: the clip's and the source file's.
  const std::string file_frame =
      "(source file frame " + std::to_string(frame + clip->source_first_frame) + ")";
  EXPECT_NE(seen["label"].get<std::string>().find("clip frame " + std::to_string(frame) + " " +
                                                  file_frame),
            std::string::npos)
      << seen["label"];
  const std::vector<Eigen::Vector3d> expected = ArchivePose(reader, *clip, instance.start, frame);
  const nlohmann::json& points = seen["points"];
  ASSERT_EQ(points.size(), expected.size());
  const double tolerance = 2e-3 * RestPoseExtent(reader.skeleton());
  double worst = 0;
  for (size_t idx = 0; idx < expected.size(); ++idx) {
    for (int axis = 0; axis < 3; ++axis) {
      worst = std::max(worst, std::abs(points[idx][axis].get<double>() - expected[idx][axis]));
    }
  }
  EXPECT_LE(worst, tolerance) << "the drawn pose is not the archive's frame " << frame;
  EXPECT_GT(seen["bones"].get<int>(), 10);
  EXPECT_EQ(seen["painted"].get<int>(), seen["bones"].get<int>()) << "bones not drawn";
}

TEST(ReportPlayerBrowser, PlaysEveryInstanceOfTheFirstMotifAndScrubsToTheArchivesFrames) {
  MOTIF_REQUIRE_MOCAP_DATA();
  const std::string chromium = testing::FindChromium();
  if (chromium.empty()) {
    GTEST_SKIP() << "no Chromium found (apt-get install chromium, or set MOTIF_CHROMIUM): "
                    "the player is not checked in a browser";
  }
  testing::TempDir dir;
  // A Russian dance of repeated squat bounces: its first motif has several instances.
  const std::string take = testing::MocapDir() + "/asfamc/90/90_30.amc";
  testing::RunResult mined = testing::RunTool("mine " + take + " --out " + dir.File("out"));
  ASSERT_EQ(mined.exit_code, 0) << mined.output;
  auto document = ReadMotifsJson(dir.File("out/motifs.json"));
  ASSERT_TRUE(document.ok()) << document.status().ToString();
  ASSERT_FALSE(document->motifs.empty());
  const size_t instances = document->motifs[0].instances.size();
  ASSERT_GE(instances, 2u);
  auto reader = FrameFileReader::Open(dir.File("out/archive.mfs"));
  ASSERT_TRUE(reader.ok());
  const StickFigureLayout layout = MakeStickFigureLayout((*reader)->skeleton());
  const uint32_t step = InstancePlayback(**reader, layout).step();

  auto html = ReadFileToString(dir.File("out/report.html"));
  ASSERT_TRUE(html.ok());
  const std::string instrumented = dir.File("out/report.player.html");
  const testing::InstrumentedRun run =
      testing::RunInstrumentedPage(chromium, *html, kPlayerScript, instrumented, dir.path());
  ASSERT_TRUE(run.error.empty()) << run.error;
  const nlohmann::json& result = run.result;
  EXPECT_TRUE(result["errors"].empty()) << result["errors"].dump(2);
  EXPECT_EQ(run.log.find("Uncaught"), std::string::npos) << run.log;
  ASSERT_TRUE(result["button"].get<bool>()) << "no play button on the first motif";
  ASSERT_TRUE(result["player"].get<bool>()) << "the play button opened no player";
  EXPECT_EQ(result["cells"].get<size_t>(), instances) << "not every instance is shown";
  // Playing advances the frame; pausing stops.
  EXPECT_TRUE(result["played"]["playing"].get<bool>());
  EXPECT_NE(result["played"]["frame"].get<uint64_t>(), result["start_frame"].get<uint64_t>());
  EXPECT_TRUE(result["paused"].get<bool>());
  {
    SCOPED_TRACE("scrubbed, first instance");
    EXPECT_EQ(result["scrub"]["instance"].get<size_t>(), 0u);
    ExpectArchivePose(result["scrub"], *document, **reader, step);
  }
  {
    SCOPED_TRACE("switched to the second instance and scrubbed");
    EXPECT_EQ(result["switched"]["instance"].get<size_t>(), 1u);
    ExpectArchivePose(result["switched"], *document, **reader, step);
  }

  // A screenshot of the page with the player open, for a person to look at.
  const std::filesystem::path artefacts =
      std::filesystem::absolute("report_player_browser_test_artefacts");
  std::filesystem::create_directories(artefacts);
  const std::string png = (artefacts / "player.png").string();
  std::filesystem::remove(png);
  testing::RunResult shot =
      testing::RunShell("timeout 180 " + testing::ChromiumCommand(chromium, dir.File("profile2")) +
                        "--window-size=1200,1400 --screenshot='" + png + "' 'file://" +
                        instrumented + "' >/dev/null 2>&1");
  EXPECT_EQ(shot.exit_code, 0);
  std::cout << "[ artefact ] screenshot of the player (" << instances
            << " instances of motif 0): " << png << "\n";
}

}  // namespace
}  // namespace motif
