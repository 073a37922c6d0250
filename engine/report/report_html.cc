#include "engine/report/report_html.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include <nlohmann/json.hpp>

#include "common/duration_text.h"
#include "common/file_util.h"
#include "engine/report/aligned_keyframes.h"
#include "engine/report/instance_alignment.h"
#include "engine/report/instance_playback.h"
#include "engine/report/instance_player_script.h"
#include "engine/report/keyframe_figures.h"
#include "engine/report/limb_side.h"
#include "engine/report/motifs_archive_check.h"
#include "formats/motion/quaternion_math.h"

namespace motif {

namespace {

// Global [start, end) of an instance.
struct GlobalRange {
  uint64_t start = 0;
  uint64_t end = 0;
};

// Up to `count` instances of `motif` to draw: first one per clip (in order), so the strips show
// the motif as different takes perform it, then the rest in order.
std::vector<size_t> ChooseInstances(const MotifsJsonMotif& motif, size_t count) {
  std::vector<size_t> chosen;
  std::unordered_set<std::string> clips;
  for (size_t idx = 0; idx < motif.instances.size() && chosen.size() < count; ++idx) {
    if (clips.insert(motif.instances[idx].clip).second) chosen.push_back(idx);
  }
  for (size_t idx = 0; idx < motif.instances.size() && chosen.size() < count; ++idx) {
    if (std::find(chosen.begin(), chosen.end(), idx) == chosen.end()) chosen.push_back(idx);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

// One instance strip to draw.
struct FigureJob {
  size_t motif_idx = 0;
  size_t slot = 0;  // index into the motif's chosen instances
  const ClipInfo* clip = nullptr;
  uint64_t start = 0;  // within the clip
  uint64_t end = 0;
};

// A click on a timeline instance goes to its motif. The lazy motifs' figures are drawn from the
// JSON block (format: EncodeFigurePoints) when they come near the viewport; the SVG it writes is
// the same as StickFigureSvg's.
constexpr char kScript[] = R"js(
(function(){
document.addEventListener('click',function(e){var r=e.target.closest&&e.target.closest('.tl rect');if(r)location.hash='m'+r.getAttribute('class').slice(1);});
var el=document.getElementById('pose-data');if(!el)return;
var D=JSON.parse(el.textContent),K=D.strokes,P=D.points,A='ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_',V={};
for(var i=0;i<64;i++)V[A.charAt(i)]=i;
function c(s,i){return (V[s.charAt(i)]*64+V[s.charAt(i+1)]+D.min)/10;}
function fig(s,o){var h='';for(var a=0;a<K.length;a++){var d='',R=K[a].runs;for(var r=0;r<R.length;r++){var ch=R[r];
for(var b=0;b<ch.length;b++){var j=o+4*ch[b];d+=(b?'L':'M')+c(s,j)+' '+c(s,j+2);}}h+='<path stroke="'+K[a].colour+'" d="'+d+'"/>';}
return '<svg class="fig" width="'+D.w+'" height="'+D.h+'" viewBox="0 0 '+D.w+' '+D.h+'">'+h+'</svg>';}
function render(box){if(box.getAttribute('data-done'))return;box.setAttribute('data-done','1');
var m=D.motifs[box.getAttribute('data-m')]||[],f=box.querySelectorAll('.figs');
for(var s=0;s<f.length&&s<m.length;s++){var h='';for(var o=0;o<m[s].length;o+=4*P)h+=fig(m[s],o);f[s].innerHTML=h;}}
var boxes=Array.prototype.slice.call(document.querySelectorAll('.insts[data-m]'));
if('IntersectionObserver' in window){var io=new IntersectionObserver(function(es){es.forEach(function(e){if(e.isIntersecting){render(e.target);io.unobserve(e.target);}});},{rootMargin:'1000px'});boxes.forEach(function(b){io.observe(b);});}
else boxes.forEach(render);
var all=document.getElementById('draw-all');if(all)all.onclick=function(){boxes.forEach(render);};
})();
)js";

// The player's data for every instance of every motif, in rank order while the budget lasts:
// per motif a JSON text ("" when over budget), and the figure. No "</" inside (script blocks).
struct PlaybackBlocks {
  std::vector<std::string> motifs;
  std::string figure;
};

// Which motifs get playback: in rank order while the estimated bytes fit the budget (base64 of
// 3 int16 a point a sample, and about 5 characters per alignment entry).
std::vector<bool> MotifsWithPlayback(const MotifsDocument& document, uint32_t step, size_t points,
                                     uint64_t budget) {
  std::vector<bool> chosen;
  uint64_t used = 0;
  for (const MotifsJsonMotif& motif : document.motifs) {
    uint64_t samples = 0;
    for (const MotifsJsonInstance& instance : motif.instances) {
      samples += (instance.length() - 1) / step + 1;
    }
    const uint64_t reference =
        motif.instances.empty() ? 0 : (motif.instances[0].length() - 1) / step + 1;
    const uint64_t bytes = samples * points * 8 + motif.instances.size() * reference * 5;
    // Over the budget, no later (smaller) motif jumps ahead: the rank order is kept.
    const bool fits = used + bytes <= budget;
    used = fits ? used + bytes : budget;
    chosen.push_back(fits && !motif.instances.empty());
  }
  return chosen;
}

// One motif's player data: its instances (encoded), each aligned to the first.
std::string PlaybackJson(const MotifsJsonMotif& motif, const std::vector<PlaybackInstance>& encoded,
                         const FrameFileReader& reader, size_t stride, const std::string& archive,
                         const std::unordered_map<std::string, const ClipInfo*>& clips) {
  nlohmann::json instances = nlohmann::json::array();
  for (size_t idx = 0; idx < encoded.size(); ++idx) {
    const PlaybackInstance& data = encoded[idx];
    const ClipInfo& clip = *clips.at(motif.instances[idx].clip);
    // Each instance's sample shown with each of the first instance's (the motif's time).
    const std::vector<uint32_t> align =
        AlignToReference(reader.skeleton(), stride, encoded[0].sample_rows, encoded[0].samples,
                         data.sample_rows, data.samples);
    instances.push_back({{"clip", clip.name},
                         {"start", data.start},
                         {"end", data.end},
                         {"samples", data.samples},
                         {"scale", data.scale},
                         {"origin", data.origin},
                         {"heading", data.heading_rad},
                         // clip frame k is source-file frame file_first + k * file_rate
                         {"file_first", clip.source_first_frame},
                         {"file_rate", clip.fps > 0 ? clip.source_fps / clip.fps : 1.0},
                         {"align", align},
                         {"points", data.points_base64}});
  }
  std::string text = nlohmann::json({{"archive", archive}, {"instances", instances}}).dump();
  // '<' only occurs inside JSON strings: as \u003c nothing in them can end or open a tag.
  for (size_t at = text.find('<'); at != std::string::npos; at = text.find('<', at + 6)) {
    text.replace(at, 1, "\\u003c");
  }
  return text;
}

// The player's data for every instance of the motifs within the budget, per motif a JSON text
// ("" for the others), and the figure. The instances are encoded in archive order (each block
// decoded about once), then grouped by motif. No '<' inside (they go in script blocks).
Result<PlaybackBlocks> PlaybackData(const MotifsDocument& document, const FrameFileReader& reader,
                                    const StickFigureLayout& layout, const std::string& archive,
                                    const std::unordered_map<std::string, const ClipInfo*>& clips,
                                    uint64_t budget) {
  InstancePlayback playback(reader, layout);
  PlaybackBlocks blocks;
  blocks.figure = playback.FigureJson();
  const std::vector<bool> chosen =
      MotifsWithPlayback(document, playback.step(), layout.points.size(), budget);
  struct Job {
    uint64_t global_start;
    size_t motif_idx;
    size_t instance_idx;
  };
  std::vector<Job> jobs;
  std::vector<std::vector<PlaybackInstance>> encoded(document.motifs.size());
  for (size_t motif_idx = 0; motif_idx < document.motifs.size(); ++motif_idx) {
    if (!chosen[motif_idx]) continue;
    const MotifsJsonMotif& motif = document.motifs[motif_idx];
    encoded[motif_idx].resize(motif.instances.size());
    for (size_t idx = 0; idx < motif.instances.size(); ++idx) {
      const MotifsJsonInstance& instance = motif.instances[idx];
      jobs.push_back({clips.at(instance.clip)->first_frame + instance.start, motif_idx, idx});
    }
  }
  std::sort(jobs.begin(), jobs.end(), [](const Job& a, const Job& b) {
    return std::tie(a.global_start, a.motif_idx, a.instance_idx) <
           std::tie(b.global_start, b.motif_idx, b.instance_idx);
  });
  for (const Job& job : jobs) {
    const MotifsJsonInstance& instance = document.motifs[job.motif_idx].instances[job.instance_idx];
    MOTIF_ASSIGN_OR_RETURN(encoded[job.motif_idx][job.instance_idx],
                           playback.Encode(*clips.at(instance.clip), instance.start, instance.end));
  }
  for (size_t motif_idx = 0; motif_idx < document.motifs.size(); ++motif_idx) {
    blocks.motifs.push_back(chosen[motif_idx]
                                ? PlaybackJson(document.motifs[motif_idx], encoded[motif_idx],
                                               reader, playback.stride(), archive, clips)
                                : std::string());
    encoded[motif_idx].clear();
    encoded[motif_idx].shrink_to_fit();
  }
  return blocks;
}

std::string ViewName(FigureView view) { return view == FigureView::kSide ? "side" : "front"; }

// "frames": how many, how long, the clips and the skeleton.
std::string OverviewFramesHtml(const FrameFileReader& reader) {
  const double fps = reader.fps();
  return WithCommas(reader.frame_count()) + " (" +
         FormatDuration(fps > 0 ? reader.frame_count() / fps : 0.0) + " at " +
         HtmlNumber("%g fps", fps) + "), " + CountOf(reader.clips().size(), "clip") +
         ", skeleton " + HtmlEscape(reader.skeleton().family()) + " (" +
         std::to_string(reader.skeleton().joint_count()) + " joints)";
}

// "parameters": plain names first, the papers' symbols beside them, each once.
std::string OverviewParametersHtml(const MotifsJsonParams& params, double fps,
                                   const std::string& parameters_text) {
  return "match radius &epsilon; " + HtmlNumber("%.4g", params.eps) +
         " &middot; neighbours kept per frame K<sub>max</sub> " + std::to_string(params.kmax) +
         " &middot; frames a path may skip B " + std::to_string(params.branch) +
         " &middot; shortest motif &lambda; " + CountOf(params.min_length, "frame") + " (" +
         HtmlSeconds(params.min_length, fps) + ") &middot; motif groups " +
         (params.groups ? std::to_string(params.groups) : std::string("automatic")) +
         " &middot; random seed " + std::to_string(params.seed) +
         (parameters_text.empty()
              ? std::string()
              : "<br><span class=\"note\">" + HtmlEscape(parameters_text) + "</span>");
}

// "timings": a row per stage and their total.
std::string OverviewTimingsHtml(const std::vector<ReportStageTiming>& timings) {
  std::string table = "<table class=\"t\">";
  double total = 0;
  for (const ReportStageTiming& timing : timings) {
    table += "<tr><td>" + HtmlEscape(timing.stage) + "</td><td>" +
             HtmlNumber("%.2f s", timing.seconds) + "</td></tr>";
    total += timing.seconds;
  }
  table += "<tr><td><b>total</b></td><td><b>" + HtmlNumber("%.2f s", total) + "</b></td></tr>";
  return table + "</table>";
}

// "planted motifs": the score against a synthetic archive's truth.
std::string OverviewPlantedHtml(const PlantedMotifScore& score, const std::string& truth_path) {
  return (truth_path.empty() ? std::string() : "<code>" + HtmlEscape(truth_path) + "</code>: ") +
         CountOf(score.planted_motifs, "motif") + ", " + CountOf(score.planted, "instance") +
         "; recall " + HtmlNumber("%.3f", score.recall) + " (" + WithCommas(score.planted_hit) +
         " hit), precision " + HtmlNumber("%.3f", score.precision) + " (" +
         WithCommas(score.found_hitting) + " of " + WithCommas(score.found) +
         " found instances), adjusted Rand index " + HtmlNumber("%.3f", score.adjusted_rand_index);
}

void AppendOverview(const MotifsDocument& document, const FrameFileReader& reader,
                    const ReportInfo& info, const ReportOptions& options, uint64_t instance_count,
                    uint64_t covered_frames, std::string* html) {
  const std::string archive = info.archive_path.empty() ? document.archive : info.archive_path;
  std::string& out = *html;
  out += "<section id=\"overview\"><h2>Overview</h2><table class=\"kv\">\n";
  auto row = [&](const std::string& key, const std::string& value_html) {
    out += HtmlRow(key, value_html);
  };
  row("archive", "<code>" + HtmlEscape(archive) + "</code>");
  row("frames", OverviewFramesHtml(reader));
  row("parameters", OverviewParametersHtml(document.params, reader.fps(), info.parameters_text));
  if (!info.timings.empty()) row("timings", OverviewTimingsHtml(info.timings));
  if (info.peak_memory_bytes > 0) row("peak memory", HtmlBytes(info.peak_memory_bytes));
  row("motifs",
      CountOf(document.motifs.size(), "motif") + ", " + CountOf(instance_count, "instance"));
  row("coverage",
      WithCommas(covered_frames) + " frames in some instance (" +
          HtmlNumber("%.1f%%", reader.frame_count() ? 100.0 * static_cast<double>(covered_frames) /
                                                          reader.frame_count()
                                                    : 0.0) +
          " of the archive)");
  if (info.planted_score) {
    row("planted motifs", OverviewPlantedHtml(*info.planted_score, info.truth_path));
  }
  row("figures", ViewName(options.view) + " view, heading removed; " +
                     std::to_string(options.keyframes) +
                     " keyframes per instance at the same moments of each: evenly spaced over the "
                     "first instance, mapped to the others through their time alignment to it "
                     "(as the player aligns them); left limbs blue, right red; "
                     "up to " +
                     std::to_string(options.instances_per_motif) + " instances per motif");
  out +=
      "</table>\n<p class=\"note\">Frame ranges are 0-based within their clip, the end "
      "excluded (as in motifs.json). Write a motif's instances as BVH files with "
      "<code>motifmine export-motif DIR --motif ID --out FOLDER</code>.</p></section>\n";
}

// The timeline's time axis: the bars are to the scale of the longest clip, `longest` frames; a
// tick every 1, 2 or 5 times a power of ten seconds (or 15 s, 30 s, minutes), 4 to 10 of them.
void AppendTimeAxis(uint64_t longest, double fps, std::string* html) {
  if (fps <= 0) return;
  const double seconds = static_cast<double>(longest) / fps;
  static constexpr double kSteps[] = {0.1, 0.2, 0.5, 1,   2,    5,    10,   15,   30,
                                      60,  120, 300, 600, 1800, 3600, 7200, 18000};
  double step = kSteps[0];
  for (double candidate : kSteps) {
    step = candidate;
    if (seconds / candidate <= 10) break;
  }
  std::string& out = *html;
  out +=
      "<div class=\"tlrow\"><span class=\"n\">time</span><span class=\"w\"><div "
      "class=\"axis\">";
  for (int tick = 0; tick * step <= seconds + 1e-9; ++tick) {
    const double at = tick * step;
    const std::string label =
        step >= 60 ? HtmlNumber("%g min", at / 60) : HtmlNumber(step < 1 ? "%.1f s" : "%g s", at);
    out += "<span style=\"left:" + HtmlNumber("%.2f", 100.0 * at / seconds) + "%\">" + label +
           "</span>";
  }
  out += "</div></span></div>\n";
}

// An instance on the timeline.
struct TimelineMark {
  uint64_t start = 0;
  uint64_t end = 0;
  uint32_t motif_id = 0;
};

// One clip's bar, `longest` frames to the full width: a rectangle per instance.
void AppendTimelineBar(const ClipInfo& clip, std::vector<TimelineMark>* clip_marks,
                       uint64_t longest, double fps, std::string* html) {
  std::string& out = *html;
  std::sort(clip_marks->begin(), clip_marks->end(),
            [](const TimelineMark& a, const TimelineMark& b) { return a.start < b.start; });
  const std::string name = HtmlEscape(clip.name);
  const double width_percent =
      std::max(2.0, 100.0 * static_cast<double>(clip.frame_count) / longest);
  // The take's description, when the import was given one, after its name.
  const std::string described =
      clip.description.empty() ? std::string() : " \u2014 " + HtmlEscape(clip.description);
  out += "<div class=\"tlrow\"><span class=\"n\" title=\"" + name + described + " (" +
         CountOf(clip.frame_count, "frame") + ")\">" + name +
         (described.empty() ? "" : "<small>" + described + "</small>") +
         "</span><span class=\"w\"><svg " +
         "class=\"tl\" style=\"width:" + HtmlNumber("%.1f", width_percent) + "%\" viewBox=\"0 0 " +
         std::to_string(clip.frame_count) + " 1\" preserveAspectRatio=\"none\">";
  for (const TimelineMark& mark : *clip_marks) {
    const std::string id = std::to_string(mark.motif_id);
    // The colour comes from the motif's class; a click is handled by the page's script. Both
    // keep the thousands of rectangles of a large archive short.
    out += "<rect class=\"c" + id + "\" x=\"" + std::to_string(mark.start) + "\" width=\"" +
           std::to_string(mark.end - mark.start) + "\" height=\"1\"><title>motif " + id +
           ", frames " + std::to_string(mark.start) + "\u2013" + std::to_string(mark.end) + " (" +
           HtmlSeconds(mark.end - mark.start, fps) + ")</title></rect>";
  }
  out += "</svg></span></div>\n";
}

void AppendTimeline(const MotifsDocument& document, const std::vector<ClipInfo>& clips,
                    double fps, std::string* html) {
  std::unordered_map<std::string, std::vector<TimelineMark>> marks;
  for (const MotifsJsonMotif& motif : document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      marks[instance.clip].push_back({instance.start, instance.end, motif.id});
    }
  }
  uint64_t longest = 1;
  for (const ClipInfo& clip : clips) longest = std::max(longest, clip.frame_count);
  std::string& out = *html;
  out +=
      "<section id=\"timeline\"><h2>Timeline</h2><p class=\"note\">One bar per clip that "
      "holds instances, its length to scale; each rectangle is an instance, coloured by "
      "motif. Hover for its frames, click to go to its motif.</p>\n";
  AppendTimeAxis(longest, fps, &out);
  std::vector<const ClipInfo*> empty_clips;
  for (const ClipInfo& clip : clips) {
    auto found = marks.find(clip.name);
    if (found == marks.end()) {
      empty_clips.push_back(&clip);
      continue;
    }
    AppendTimelineBar(clip, &found->second, longest, fps, &out);
  }
  if (!empty_clips.empty()) {
    out += "<details><summary>" + CountOf(empty_clips.size(), "clip") +
           " without instances</summary><p class=\"note\">";
    for (size_t idx = 0; idx < empty_clips.size(); ++idx) {
      if (idx > 0) out += ", ";
      out += HtmlEscape(empty_clips[idx]->name);
    }
    out += "</p></details>\n";
  }
  out += "</section>\n";
}

using ReportClipsByName = std::unordered_map<std::string, const ClipInfo*>;

uint64_t CountInstances(const MotifsDocument& document) {
  uint64_t instance_count = 0;
  for (const MotifsJsonMotif& motif : document.motifs) instance_count += motif.instances.size();
  return instance_count;
}

// Frames of the archive inside some instance: instances overlap (within and across motifs), so
// their global ranges are merged in start order and each frame counts once.
uint64_t CoveredFrames(const MotifsDocument& document, const ReportClipsByName& clips_by_name) {
  std::vector<GlobalRange> ranges;
  for (const MotifsJsonMotif& motif : document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      const uint64_t first = clips_by_name.at(instance.clip)->first_frame;
      ranges.push_back({first + instance.start, first + instance.end});
    }
  }
  std::sort(ranges.begin(), ranges.end(),
            [](const GlobalRange& a, const GlobalRange& b) { return a.start < b.start; });
  uint64_t covered_frames = 0;
  uint64_t covered_until = 0;
  for (const GlobalRange& range : ranges) {
    const uint64_t from = std::max(range.start, covered_until);
    if (range.end > from) covered_frames += range.end - from;
    covered_until = std::max(covered_until, range.end);
  }
  return covered_frames;
}

// The instances drawn for each motif (ChooseInstances), their keyframes' clip frames (at aligned
// moments: aligned_keyframes.h) and their strips: SVG for the eager motifs, encoded points
// (EncodeFigurePoints) for the page's script to draw.
struct FigureStrips {
  std::vector<std::vector<size_t>> chosen;                 // per motif, indices into instances
  std::vector<std::vector<std::vector<uint64_t>>> frames;  // per motif, per chosen instance
  std::vector<std::vector<std::string>> strips;            // per motif, per chosen instance
};

// One job per drawn instance, in archive order so that each block is decoded about once.
std::vector<FigureJob> FigureJobsInArchiveOrder(const MotifsDocument& document,
                                                const std::vector<std::vector<size_t>>& chosen,
                                                const ReportClipsByName& clips_by_name) {
  std::vector<FigureJob> jobs;
  for (size_t motif_idx = 0; motif_idx < document.motifs.size(); ++motif_idx) {
    const MotifsJsonMotif& motif = document.motifs[motif_idx];
    for (size_t slot = 0; slot < chosen[motif_idx].size(); ++slot) {
      const MotifsJsonInstance& instance = motif.instances[chosen[motif_idx][slot]];
      jobs.push_back(
          {motif_idx, slot, clips_by_name.at(instance.clip), instance.start, instance.end});
    }
  }
  std::sort(jobs.begin(), jobs.end(), [](const FigureJob& a, const FigureJob& b) {
    const uint64_t a_start = a.clip->first_frame + a.start;
    const uint64_t b_start = b.clip->first_frame + b.start;
    return a_start != b_start ? a_start < b_start
                              : std::tie(a.motif_idx, a.slot) < std::tie(b.motif_idx, b.slot);
  });
  return jobs;
}

// The samples' rows of each motif's reference (its first instance, always chosen first: slot
// 0), which every other drawn instance of the motif is aligned to.
Result<std::vector<std::vector<float>>> ReferenceRows(const std::vector<FigureJob>& jobs,
                                                      size_t motif_count, uint32_t step,
                                                      KeyframeFigures& renderer) {
  std::vector<std::vector<float>> rows(motif_count);
  for (const FigureJob& job : jobs) {
    if (job.slot != 0) continue;
    MOTIF_ASSIGN_OR_RETURN(rows[job.motif_idx],
                           renderer.SampleRows(*job.clip, job.start, job.end, step));
  }
  return rows;
}

Result<FigureStrips> DrawFigureStrips(const MotifsDocument& document, const ReportOptions& options,
                                      const ReportClipsByName& clips_by_name,
                                      const FrameFileReader& reader, KeyframeFigures& renderer) {
  FigureStrips figures;
  const size_t motif_count = document.motifs.size();
  figures.chosen.resize(motif_count);
  figures.frames.resize(motif_count);
  figures.strips.resize(motif_count);
  for (size_t motif_idx = 0; motif_idx < motif_count; ++motif_idx) {
    figures.chosen[motif_idx] =
        ChooseInstances(document.motifs[motif_idx], options.instances_per_motif);
    figures.frames[motif_idx].resize(figures.chosen[motif_idx].size());
    figures.strips[motif_idx].resize(figures.chosen[motif_idx].size());
  }
  const std::vector<FigureJob> jobs =
      FigureJobsInArchiveOrder(document, figures.chosen, clips_by_name);
  const uint32_t step = PlaybackStep(reader.fps());
  const size_t stride = reader.layout().stride();
  MOTIF_ASSIGN_OR_RETURN(const std::vector<std::vector<float>> reference_rows,
                         ReferenceRows(jobs, motif_count, step, renderer));
  const FigureProjection& projection = renderer.projection();
  for (const FigureJob& job : jobs) {
    const std::vector<float>& reference = reference_rows[job.motif_idx];
    const auto reference_samples = static_cast<uint32_t>(reference.size() / stride);
    std::vector<uint32_t> align;  // empty for the reference itself: the identity
    if (job.slot != 0) {
      MOTIF_ASSIGN_OR_RETURN(const std::vector<float> rows,
                             renderer.SampleRows(*job.clip, job.start, job.end, step));
      align = AlignToReference(reader.skeleton(), stride, reference, reference_samples, rows,
                               static_cast<uint32_t>(rows.size() / stride));
    }
    std::vector<uint64_t>& frames = figures.frames[job.motif_idx][job.slot];
    frames = AlignedKeyframeFrames(ReferenceKeySamples(reference_samples, options.keyframes), align,
                                   job.start, step);
    MOTIF_ASSIGN_OR_RETURN(std::vector<std::vector<FigurePoint>> keyframes,
                           renderer.ProjectFrames(*job.clip, frames));
    std::string& strip = figures.strips[job.motif_idx][job.slot];
    const bool eager = job.motif_idx < options.eager_motifs;
    for (const std::vector<FigurePoint>& points : keyframes) {
      strip += eager ? StickFigureSvg(renderer.layout(), points, projection.width_px,
                                      projection.height_px)
                     : EncodeFigurePoints(points);
    }
  }
  return figures;
}

// The page's start: a colour class per motif (the timeline, swatches and strips use it) and the
// navigation.
void AppendReportPageStart(const MotifsDocument& document, const std::string& archive,
                           std::string* html) {
  std::string motif_css;
  for (const MotifsJsonMotif& motif : document.motifs) {
    motif_css += ".c" + std::to_string(motif.id) + "{color:" + HtmlColour(motif.id) + "}\n";
  }
  *html += HtmlPageStart("motifmine report: " + archive, motif_css);
  *html +=
      "<h1>motifmine report</h1>\n<nav><a href=\"#overview\">"
      "overview</a><a href=\"#timeline\">timeline</a><a href=\"#motifs\">motifs</a></nav>\n";
}

// Writes the "Motifs" section, one <section> per motif in rank order, and gathers the lazy
// motifs' encoded strips (lazy_json()) for the pose-data block the page's script draws from.
class MotifSectionsWriter {
 public:
  MotifSectionsWriter(const MotifsDocument& document, const ReportOptions& options,
                      const ReportClipsByName& clips_by_name, const KeyframeFigures& renderer,
                      double fps, const PlaybackBlocks& playback, const FigureStrips& figures)
      : document_(document),
        options_(options),
        clips_by_name_(clips_by_name),
        renderer_(renderer),
        fps_(fps),
        playback_(playback),
        figures_(figures) {}

  void Append(std::string* html) {
    *html += "<section id=\"motifs\"><h2>Motifs</h2>";
    if (document_.motifs.empty()) *html += "<p>No motifs were found.</p>";
    if (document_.motifs.size() > options_.eager_motifs) {
      *html += "<p class=\"note\">Figures of motifs after the first " +
               std::to_string(options_.eager_motifs) +
               " are drawn as they scroll into view. <button id=\"draw-all\" type=\"button\">"
               "Draw all figures</button> (before printing)</p>";
    }
    *html += "\n";
    for (size_t motif_idx = 0; motif_idx < document_.motifs.size(); ++motif_idx) {
      AppendMotif(motif_idx, html);
    }
    *html += "</section>\n";
  }

  // "id":["strip",...] per lazy motif, comma-separated; empty when every motif is eager.
  const std::string& lazy_json() const { return lazy_json_; }

 private:
  void AppendMotif(size_t motif_idx, std::string* html) {
    const MotifsJsonMotif& motif = document_.motifs[motif_idx];
    const std::string id = std::to_string(motif.id);
    const size_t count = motif.instances.size();
    *html += "<section class=\"motif\" id=\"m" + id + "\"><h3><span class=\"sw c" + id +
             "\"></span>motif " + id + "</h3><p class=\"meta\">";
    AppendLengthsAndClips(motif, html);
    *html += "</p><div class=\"playbox\">";
    AppendPlayBox(motif_idx, html);
    const bool eager = motif_idx < options_.eager_motifs;
    *html += "</div><div class=\"insts c" + id + "\"" +
             (eager ? std::string() : " data-m=\"" + id + "\"") + ">";
    AppendStrips(motif_idx, html);
    *html += "</div>";
    const size_t drawn = figures_.chosen[motif_idx].size();
    if (count > drawn) {
      const size_t more = count - drawn;
      *html += "<p class=\"note\">" + WithCommas(more) +
               (more == 1 ? " more instance not drawn" : " more instances not drawn") +
               " (all of them are in the timeline above and in motifs.json).</p>";
    }
    *html += "</section>\n";
  }

  // "N instances · M frames (s) on average, shortest–longest · C clips: names".
  void AppendLengthsAndClips(const MotifsJsonMotif& motif, std::string* html) const {
    uint64_t total_frames = 0;
    uint64_t shortest = UINT64_MAX;
    uint64_t longest = 0;
    std::vector<std::string> clip_names;
    std::unordered_set<std::string> seen_clips;
    for (const MotifsJsonInstance& instance : motif.instances) {
      total_frames += instance.length();
      shortest = std::min(shortest, instance.length());
      longest = std::max(longest, instance.length());
      if (seen_clips.insert(instance.clip).second) clip_names.push_back(instance.clip);
    }
    const size_t count = motif.instances.size();
    const uint64_t mean = count ? (total_frames + count / 2) / count : 0;
    *html += WithCommas(count) + (count == 1 ? " instance" : " instances") + " &middot; " +
             WithCommas(mean) + " frames (" + HtmlSeconds(mean, fps_) + ") on average";
    if (count > 1 && shortest != longest) {
      *html += ", " + WithCommas(shortest) + "\u2013" + WithCommas(longest);
    }
    *html += " &middot; " + WithCommas(clip_names.size()) +
             (clip_names.size() == 1 ? " clip: " : " clips: ");
    AppendClipNames(clip_names, html);
  }

  // The first clip_names_per_motif clips, each with its description, then "+N more".
  void AppendClipNames(const std::vector<std::string>& clip_names, std::string* html) const {
    for (size_t idx = 0; idx < clip_names.size() && idx < options_.clip_names_per_motif; ++idx) {
      if (idx > 0) *html += ", ";
      *html += HtmlEscape(clip_names[idx]);
      const std::string& description = clips_by_name_.at(clip_names[idx])->description;
      if (!description.empty()) *html += " (" + HtmlEscape(description) + ")";
    }
    if (clip_names.size() > options_.clip_names_per_motif) {
      *html += " +" + WithCommas(clip_names.size() - options_.clip_names_per_motif) + " more";
    }
  }

  // The play button, or why this motif has no player in the page.
  void AppendPlayBox(size_t motif_idx, std::string* html) const {
    const MotifsJsonMotif& motif = document_.motifs[motif_idx];
    const size_t count = motif.instances.size();
    if (motif.instances.empty()) {
      // nothing to play
    } else if (options_.playback_bytes == 0) {
      *html += "<p class=\"note\">No player in this page (<code>--playback-mb 0</code>).</p>";
    } else if (playback_.motifs[motif_idx].empty()) {
      *html += "<p class=\"note\">Playback of this motif is not in the page (over its " +
               HtmlBytes(options_.playback_bytes) +
               " of playback data): <code>motifmine report DIR --playback-mb N</code> raises "
               "the limit.</p>";
    } else {
      *html +=
          "<button type=\"button\" class=\"play\" data-play=\"" + std::to_string(motif.id) +
          "\">&#9654; play " +
          (count == 1 ? std::string("the instance") : "all " + WithCommas(count) + " instances") +
          "</button>";
    }
  }

  // A labelled strip per drawn instance: its figures inline when the motif is eager, else in
  // lazy_json_ (the strip's box stays empty until the script fills it).
  void AppendStrips(size_t motif_idx, std::string* html) {
    const MotifsJsonMotif& motif = document_.motifs[motif_idx];
    const std::vector<size_t>& chosen = figures_.chosen[motif_idx];
    const std::vector<std::string>& strips = figures_.strips[motif_idx];
    const bool eager = motif_idx < options_.eager_motifs;
    if (!eager) {
      if (!lazy_json_.empty()) lazy_json_ += ",\n";
      lazy_json_ += "\"" + std::to_string(motif.id) + "\":[";
    }
    for (size_t slot = 0; slot < chosen.size(); ++slot) {
      const MotifsJsonInstance& instance = motif.instances[chosen[slot]];
      std::string keyframes;
      for (uint64_t frame : figures_.frames[motif_idx][slot]) {
        keyframes += (keyframes.empty() ? "" : " \u00b7 ") + std::to_string(frame);
      }
      *html += "<div class=\"strip\"><div class=\"lbl\">" + HtmlEscape(instance.clip) + " " +
               std::to_string(instance.start) + "\u2013" + std::to_string(instance.end) + " (" +
               HtmlSeconds(instance.length(), fps_) + ")<br><span class=\"kf\">frames " +
               keyframes + "</span></div><div class=\"figs\">" +
               (eager ? strips[slot] : std::string()) + "</div></div>";
      if (!eager) {
        if (slot > 0) lazy_json_ += ",";
        lazy_json_ += "\"" + strips[slot] + "\"";
      }
    }
    if (!eager) lazy_json_ += "]";
  }

  const MotifsDocument& document_;
  const ReportOptions& options_;
  const ReportClipsByName& clips_by_name_;
  const KeyframeFigures& renderer_;
  const double fps_;
  const PlaybackBlocks& playback_;
  const FigureStrips& figures_;
  std::string lazy_json_;
};

// The lazy motifs' strips with what the script needs to draw them (format: kScript's fig()):
// the figure's size, points per figure, the coordinates' offset, the layout's chains and its
// strokes (FigureStrokes: per side its colour and runs, as StickFigureSvg strokes them).
void AppendPoseData(const std::string& lazy_json, const KeyframeFigures& renderer,
                    std::string* html) {
  if (lazy_json.empty()) return;
  const StickFigureLayout& layout = renderer.layout();
  const FigureProjection& projection = renderer.projection();
  *html += "<script type=\"application/json\" id=\"pose-data\">{\"w\":" +
           FormatFigureCoord(projection.width_px) +
           ",\"h\":" + FormatFigureCoord(projection.height_px) +
           ",\"points\":" + std::to_string(layout.points.size()) +
           ",\"min\":" + std::to_string(std::lround(kFigureCoordMin * 10)) + ",\"chains\":[";
  for (size_t chain_idx = 0; chain_idx < layout.chains.size(); ++chain_idx) {
    *html += chain_idx ? ",[" : "[";
    for (size_t step = 0; step < layout.chains[chain_idx].size(); ++step) {
      if (step > 0) *html += ",";
      *html += std::to_string(layout.chains[chain_idx][step]);
    }
    *html += "]";
  }
  *html += "],\"strokes\":[";
  const std::vector<FigureStroke> strokes = FigureStrokes(layout);
  for (size_t stroke_idx = 0; stroke_idx < strokes.size(); ++stroke_idx) {
    *html += std::string(stroke_idx ? "," : "") + "{\"colour\":\"" +
             LimbSideColour(strokes[stroke_idx].side) + "\",\"runs\":[";
    const std::vector<std::vector<uint32_t>>& runs = strokes[stroke_idx].runs;
    for (size_t run_idx = 0; run_idx < runs.size(); ++run_idx) {
      *html += run_idx ? ",[" : "[";
      for (size_t step = 0; step < runs[run_idx].size(); ++step) {
        if (step > 0) *html += ",";
        *html += std::to_string(runs[run_idx][step]);
      }
      *html += "]";
    }
    *html += "]}";
  }
  *html += "],\"motifs\":{\n" + lazy_json + "}}</script>\n";
}

// The player's data after the page's content, decoded only when a player opens; none, and no
// player script, when no motif has a player. Then the page's scripts.
void AppendPlaybackAndScripts(const MotifsDocument& document, const PlaybackBlocks& playback,
                              std::string* html) {
  const bool any_player = std::any_of(playback.motifs.begin(), playback.motifs.end(),
                                      [](const std::string& motif) { return !motif.empty(); });
  if (any_player) {
    *html +=
        "<script type=\"application/json\" id=\"play-figure\">" + playback.figure + "</script>\n";
  }
  for (size_t motif_idx = 0; motif_idx < document.motifs.size(); ++motif_idx) {
    if (playback.motifs[motif_idx].empty()) continue;
    *html += "<script type=\"application/json\" id=\"play-" +
             std::to_string(document.motifs[motif_idx].id) + "\">" + playback.motifs[motif_idx] +
             "</script>\n";
  }
  *html += std::string("<script>") + kScript + "</script>\n";
  if (any_player) *html += std::string("<script>") + kInstancePlayerScript + "</script>\n";
}

// The archive's clips with the descriptions given to the run over the stored ones.
std::vector<ClipInfo> DescribedClips(const FrameFileReader& reader, const ReportInfo& info) {
  std::vector<ClipInfo> clips = reader.clips();
  for (ClipInfo& clip : clips) {
    if (auto given = info.descriptions.find(clip.name); given != info.descriptions.end()) {
      clip.description = given->second;
    }
  }
  return clips;
}

}  // namespace

Result<std::string> ReportHtmlText(const MotifsDocument& document, const FrameFileReader& reader,
                                   const ReportInfo& info, const ReportOptions& options) {
  MOTIF_RETURN_IF_ERROR(CheckMotifsMatchArchive(document, "the motifs document", reader));
  const std::vector<ClipInfo> clips = DescribedClips(reader, info);
  ReportClipsByName clips_by_name;
  for (const ClipInfo& clip : clips) clips_by_name.emplace(clip.name, &clip);
  const uint64_t instance_count = CountInstances(document);
  const uint64_t covered_frames = CoveredFrames(document, clips_by_name);
  KeyframeFigures renderer(reader, options.view, options.keyframes);
  MOTIF_ASSIGN_OR_RETURN(FigureStrips figures,
                         DrawFigureStrips(document, options, clips_by_name, reader, renderer));

  const std::string archive = info.archive_path.empty() ? document.archive : info.archive_path;
  std::string html;
  html.reserve(1 << 20);
  AppendReportPageStart(document, archive, &html);
  AppendOverview(document, reader, info, options, instance_count, covered_frames, &html);
  AppendTimeline(document, clips, reader.fps(), &html);
  MOTIF_ASSIGN_OR_RETURN(PlaybackBlocks playback,
                         PlaybackData(document, reader, renderer.layout(), archive, clips_by_name,
                                      options.playback_bytes));
  MotifSectionsWriter sections(document, options, clips_by_name, renderer, reader.fps(), playback,
                               figures);
  sections.Append(&html);
  AppendPoseData(sections.lazy_json(), renderer, &html);
  AppendPlaybackAndScripts(document, playback, &html);
  html += HtmlPageEnd();
  return html;
}

Status WriteReportHtml(const std::string& path, const MotifsDocument& document,
                       const FrameFileReader& reader, const ReportInfo& info,
                       const ReportOptions& options) {
  MOTIF_ASSIGN_OR_RETURN(std::string html, ReportHtmlText(document, reader, info, options));
  return AtomicWriteFile(path, html);
}

}  // namespace motif
