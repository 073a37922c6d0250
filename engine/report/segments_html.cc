#include "engine/report/segments_html.h"

#include "common/file_util.h"
#include "engine/report/html_page.h"
#include "engine/report/keyframe_figures.h"
#include "engine/signature/take_retrieval.h"

namespace motif {
namespace {

constexpr char kSegmentsCss[] = R"css(
.timeline{display:flex;height:22px;width:100%;border:1px solid #ccc;margin:4px 0 8px}
.timeline div{height:100%;border-right:1px solid #fff;box-sizing:border-box}
.legend span{display:inline-block;margin:0 12px 4px 0}
.legend i{display:inline-block;width:14px;height:14px;vertical-align:middle;margin-right:4px}
.seg{border-top:1px solid #ddd;padding:6px 0 2px}
.seg h3{margin:0;font-size:14px}
.seg h3 i{display:inline-block;width:12px;height:12px;margin-right:6px}
.take{margin-top:18px}
)css";

constexpr char kUnlabelledColour[] = "#bbb";

std::string ColourOf(uint32_t label) {
  return label == kUnlabelled ? kUnlabelledColour : HtmlColour(label);
}

std::string NameOf(const Segmentation& result, uint32_t label) {
  return label == kUnlabelled ? "(no label)" : result.label_names[label];
}

// How two windows are compared, for the method row.
std::string WindowDistanceText(const Segmentation& result, const SegmentsPageInfo& info) {
  if (result.distance == "dtw") return "DTW over the windows' frames";
  if (result.signature == "words") {
    return "the EMD between the windows' bags of words (every word its own bin, the DTW between "
           "words as ground distance)";
  }
  return "the EMD between the windows' TF-IDF signatures over " + std::to_string(info.motifs) +
         " motifs";
}

// What the unsupervised segmentation compares, for the method row.
std::string UnsupervisedSignatureText(const Segmentation& result, const SegmentsPageInfo& info) {
  if (result.signature == "words") {
    return "mean affinity profiles (each word's kernel affinity to every word, by DTW)";
  }
  return "TF-IDF signatures over " + std::to_string(info.motifs) + " motifs";
}

std::string Overview(const Segmentation& result, const FrameFileReader& reader,
                     const SegmentsPageInfo& info) {
  uint64_t segments = 0;
  for (const SegmentedTake& take : result.takes) segments += take.segments.size();
  std::string html = "<section id=\"overview\"><h2>Overview</h2><table class=\"kv\">";
  html += HtmlRow("archive", "<code>" + HtmlEscape(info.archive) + "</code> (" +
                                 CountOf(reader.clips().size(), "clip") + ")");
  std::string how;
  if (result.supervised) {
    how = "each motion word takes the majority label of the " + std::to_string(result.knn) +
          (result.one_per_take ? " nearest takes (each at its nearest window of "
                               : " nearest windows of ") +
          std::to_string(result.window) + (result.one_per_take ? " words)" : " words") + " among " +
          WithCommas(result.reference_windows) + " windows of " +
          CountOf(result.reference_takes, "labelled take") + " (labels from <code>" +
          HtmlEscape(info.labels_path) + "</code>; a take never votes " + "for itself), by " +
          WindowDistanceText(result, info);
  } else {
    how = "unsupervised: boundaries where the " + UnsupervisedSignatureText(result, info) +
          " of the " + std::to_string(result.window) + " words before and after differ most (" +
          result.distance + " distance above " + HtmlNumber("%.4f", result.threshold) +
          "), segments grouped by the same signature (" + result.linkage + " linkage within " +
          HtmlNumber("%.4f", result.group_threshold) + ")";
  }
  html += HtmlRow("method", how);
  html += HtmlRow("result", CountOf(result.takes.size(), "take") + " in " +
                                CountOf(segments, "segment") + ", " +
                                CountOf(result.label_names.size(), "label"));
  if (!result.skipped_clips.empty()) {
    html += HtmlRow("skipped", CountOf(result.skipped_clips.size(), "take") +
                                   " shorter than one motion word");
  }
  html += HtmlRow("time", HtmlNumber("%.2f s", info.seconds));
  html += "</table>\n<div class=\"legend\">";
  for (uint32_t label = 0; label < result.label_names.size(); ++label) {
    html += "<span><i style=\"background:" + ColourOf(label) + "\"></i>" +
            HtmlEscape(result.label_names[label]) + "</span>";
  }
  return html + "</div></section>\n";
}

std::string Timeline(const Segmentation& result, const SegmentedTake& take, double fps,
                     uint64_t frames) {
  std::string html = "<div class=\"timeline\">";
  for (const LabelledSegment& segment : take.segments) {
    const double percent =
        100.0 * static_cast<double>(segment.end - segment.start) / static_cast<double>(frames);
    html += "<div style=\"width:" + HtmlNumber("%.3f", percent) +
            "%;background:" + ColourOf(segment.label) + "\" title=\"" +
            HtmlEscape(NameOf(result, segment.label)) + ": frames " +
            std::to_string(segment.start) + "\u2013" + std::to_string(segment.end) + " (" +
            HtmlSeconds(segment.start, fps) + " to " + HtmlSeconds(segment.end, fps) + ")\"></div>";
  }
  return html + "</div>\n";
}

// Every group (label) with its member stretches, so the same activity can be found in each take.
std::string GroupsSection(const Segmentation& result, const FrameFileReader& reader) {
  const double fps = reader.fps();
  const std::vector<std::vector<GroupMember>> members = GroupMembers(result);
  std::string html =
      "<section id=\"groups\"><h2>Groups</h2><p class=\"note\">Each label with the segments "
      "that carry it, in every take: clip, frames (0-based, the end excluded).</p>\n";
  for (uint32_t label = 0; label < members.size(); ++label) {
    uint64_t frames = 0;
    std::string list;
    for (const GroupMember& member : members[label]) {
      frames += member.end - member.start;
      list += "<li><code>" + HtmlEscape(reader.clips()[member.clip].name) + "</code> frames " +
              std::to_string(member.start) + "\u2013" + std::to_string(member.end) + " (" +
              HtmlSeconds(member.end - member.start, fps) + ")</li>";
    }
    html += "<div class=\"seg\"><h3><i style=\"background:" + ColourOf(label) + "\"></i>" +
            HtmlEscape(result.label_names[label]) + " <span class=\"note\">" +
            CountOf(members[label].size(), "segment") + ", " + HtmlSeconds(frames, fps) +
            "</span></h3><ul>" + list + "</ul></div>\n";
  }
  return html + "</section>\n";
}

}  // namespace

Result<std::string> SegmentsHtmlText(const Segmentation& result, const FrameFileReader& reader,
                                     const SegmentsPageInfo& info) {
  const double fps = reader.fps();
  KeyframeFigures figures(reader, FigureView::kSide, 5);
  std::string html = HtmlPageStart("motifmine segment: " + info.archive, kSegmentsCss);
  html += "<h1>motifmine segment</h1>\n" + Overview(result, reader, info);
  html +=
      "<section id=\"takes\"><h2>Takes</h2><p class=\"note\">One timeline per take, "
      "coloured by label (hover for frames), then its segments with keyframes. Frames are "
      "0-based within the clip, the end excluded.</p>\n";
  uint64_t drawn = 0;
  for (const SegmentedTake& take : result.takes) {
    const ClipInfo& clip = reader.clips()[take.clip];
    html += "<div class=\"take\"><h3>" + HtmlEscape(clip.name) + " <span class=\"note\">" +
            CountOf(clip.frame_count, "frame") + ", " + HtmlSeconds(clip.frame_count, fps) +
            ", " + CountOf(take.segments.size(), "segment") + "</span></h3>\n";
    html += Timeline(result, take, fps, clip.frame_count);
    for (const LabelledSegment& segment : take.segments) {
      html += "<div class=\"seg\"><h3><i style=\"background:" + ColourOf(segment.label) +
              "\"></i>" + HtmlEscape(NameOf(result, segment.label)) + " <span class=\"note\">" +
              "frames " + std::to_string(segment.start) + "\u2013" + std::to_string(segment.end) +
              " (" + HtmlSeconds(segment.end - segment.start, fps) + ")</span></h3>";
      if (drawn < kMaxSegmentFigures) {
        MOTIF_ASSIGN_OR_RETURN(std::string svg, figures.Svg(clip, segment.start, segment.end));
        html += "<div class=\"figs\">" + svg + "</div>";
        ++drawn;
      }
      html += "</div>\n";
    }
    html += "</div>\n";
  }
  if (drawn == kMaxSegmentFigures) {
    html += "<p class=\"note\">Keyframes are drawn for the first " +
            WithCommas(kMaxSegmentFigures) + " segments only.</p>\n";
  }
  html += "</section>\n" + GroupsSection(result, reader);
  return html + HtmlPageEnd();
}

Status WriteSegmentsHtml(const std::string& path, const Segmentation& result,
                         const FrameFileReader& reader, const SegmentsPageInfo& info) {
  MOTIF_ASSIGN_OR_RETURN(std::string html, SegmentsHtmlText(result, reader, info));
  return AtomicWriteFile(path, html);
}

}  // namespace motif
