#include "engine/report/words_report_html.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "common/file_util.h"
#include "engine/report/html_page.h"
#include "engine/report/keyframe_figures.h"

namespace motif {
namespace {

constexpr char kWordsCss[] = R"css(
.heat{display:block;height:14px;width:100%;background:#eee}
.heat rect.best{stroke:#c00;stroke-width:2px;vector-effect:non-scaling-stroke;fill:none}
.match{border-top:1px solid #ddd;padding:8px 0 4px;margin-top:6px}
.match h3{margin:0;font-size:15px}
.map{background:#fafafa;border:1px solid #ddd}
.map circle{stroke:#fff;stroke-width:.5}
table.g{border-collapse:collapse;font-size:12px}table.g td,table.g th{border:1px solid #ddd;padding:2px 6px;text-align:right}
table.g th{background:#f3f3f3}table.g td.ok{background:#dff0d8}
table.l{border-collapse:collapse;font-size:12px}table.l td,table.l th{padding:1px 10px 1px 0;text-align:left}
.dm rect{shape-rendering:crispEdges}
)css";

// A grey for a distance between lo and hi: darker is closer.
std::string Shade(double value, double lo, double hi) {
  const double t = hi > lo ? std::clamp((value - lo) / (hi - lo), 0.0, 1.0) : 0.0;
  const int level = static_cast<int>(std::lround(30 + 205 * t));
  return "rgb(" + std::to_string(level) + "," + std::to_string(level) + "," +
         std::to_string(std::min(255, level + 20)) + ")";
}

// The query's table, and its keyframes: from the archive, or the query file fitted to it.
Status AppendSearchQuery(const SearchResult& result, const FrameFileReader& reader,
                         const SearchPageInfo& info, KeyframeFigures* figures, std::string* html) {
  *html += "<h1>motifmine search</h1>\n<section id=\"overview\"><h2>Query</h2><table class=\"kv\">";
  *html += HtmlRow("archive", "<code>" + HtmlEscape(info.archive) + "</code> (" +
                                  WithCommas(reader.clips().size()) + " clips)");
  const bool movement = result.distance == "movement";
  *html += HtmlRow("query", movement ? HtmlEscape(info.query_text)
                                     : HtmlEscape(info.query_text) + ", " +
                                           WithCommas(info.query_words) +
                                           (info.query_words == 1 ? " word" : " words"));
  *html += HtmlRow("search", movement ? "whole takes: the movement distance (what moves, how, and "
                                        "where the body goes; blind to posture, amplitude and "
                                        "tempo)"
                             : result.whole_take
                                 ? "whole takes: the EMD between take signatures over " +
                                       std::to_string(info.motifs) + " motifs"
                                 : "a window of " + WithCommas(info.query_words) +
                                       " words slid along every take, one word at a time (" +
                                       WithCommas(result.windows) + " windows); EMD over " +
                                       std::to_string(info.motifs) + " motifs");
  for (const std::string& note : info.notes) *html += HtmlRow("note", HtmlEscape(note));
  *html += HtmlRow("time", HtmlNumber("%.2f s", info.seconds));
  *html += "</table>\n";
  if (info.query_in_archive) {
    const ClipInfo& clip = reader.clips()[info.query_clip];
    MOTIF_ASSIGN_OR_RETURN(std::string svg, figures->Svg(clip, info.query_start, info.query_end));
    *html += "<div class=\"strip\"><div class=\"lbl\">" + HtmlEscape(clip.name) + " " +
             std::to_string(info.query_start) + "\u2013" + std::to_string(info.query_end) +
             "</div><div class=\"figs\">" + svg + "</div></div>\n";
  } else if (info.query_take != nullptr && info.query_take->frame_count() > 0) {
    const std::string svg = figures->TakeSvg(*info.query_take);
    *html += "<div class=\"strip\"><div class=\"lbl\">" + HtmlEscape(info.query_text) + ", " +
             CountOf(info.query_take->frame_count(), "frame") + " at the archive's rate" +
             "</div><div class=\"figs\">" + svg + "</div></div>\n";
  }
  return Status::Ok();
}

// The strip of the EMD of every window along a match's take, darker where closer (shaded
// between lo and hi); the box marks the match's window.
void AppendWindowProfile(const std::vector<float>& profile, uint64_t best_window, double lo,
                         double hi, std::string* html) {
  *html += "<svg class=\"heat\" viewBox=\"0 0 " + std::to_string(profile.size()) +
           " 1\" preserveAspectRatio=\"none\">";
  for (size_t window = 0; window < profile.size(); ++window) {
    if (std::isnan(profile[window])) continue;
    *html += "<rect x=\"" + std::to_string(window) + "\" width=\"1\" height=\"1\" fill=\"" +
             Shade(profile[window], lo, hi) + "\"><title>window at word " + std::to_string(window) +
             ": EMD " + HtmlNumber("%.4f", profile[window]) + "</title></rect>";
  }
  *html += "<rect class=\"best\" x=\"" + std::to_string(best_window) +
           "\" width=\"1\" height=\"1\"/></svg>";
}

}  // namespace

Result<std::string> SearchHtmlText(const SearchResult& result, const FrameFileReader& reader,
                                   const SearchPageInfo& info) {
  const double fps = reader.fps();
  KeyframeFigures figures(reader, FigureView::kSide, 5);
  std::string html = HtmlPageStart("motifmine search: " + info.archive, kWordsCss);
  MOTIF_RETURN_IF_ERROR(AppendSearchQuery(result, reader, info, &figures, &html));
  html += "</section>\n<section id=\"matches\"><h2>Matches</h2><p class=\"note\">";
  html += result.whole_take
              ? "Best first: every other take compared whole, one match each. Frames are 0-based "
                "within the clip, the end excluded.</p>\n"
              : "Best first, ranked across takes. A take may give several windows, none sharing "
                "a frame: its best, then its best not overlapping that one, and so on (#2, #3 "
                "...); a take of fewer words than the query is compared whole. The strip under "
                "each match shows the EMD of every window along its take, darker where closer; "
                "the box marks the match. Frames are 0-based within the clip, the end "
                "excluded.</p>\n";
  if (result.matches.empty())
    html += "<p>No window to show: every take is the query's own or holds no motion word.</p>\n";
  // One shade scale for every profile on the page.
  double lo = std::numeric_limits<double>::infinity();
  double hi = 0;
  for (const std::vector<float>& profile : result.profiles) {
    for (float value : profile) {
      if (std::isnan(value)) continue;
      lo = std::min<double>(lo, value);
      hi = std::max<double>(hi, value);
    }
  }
  for (size_t rank = 0; rank < result.matches.size(); ++rank) {
    const WindowMatch& match = result.matches[rank];
    const ClipInfo& clip = reader.clips()[match.clip];
    MOTIF_ASSIGN_OR_RETURN(std::string svg, figures.Svg(clip, match.start_frame, match.end_frame));
    html += "<div class=\"match\"><h3>" + std::to_string(rank + 1) + ". " + HtmlEscape(clip.name) +
            " <span class=\"note\">frames " + std::to_string(match.start_frame) + "\u2013" +
            std::to_string(match.end_frame) + " (" + HtmlSeconds(match.start_frame, fps) + " to " +
            HtmlSeconds(match.end_frame, fps) + "), " +
            (result.distance == "movement" ? "distance " : "EMD ") +
            HtmlNumber("%.4f", match.distance) +
            (result.whole_take  ? std::string()
             : match.whole_take ? std::string(", the whole take")
                                : ", its take's #" + std::to_string(match.rank_in_take)) +
            "</span></h3><div class=\"figs\">" + svg + "</div>";
    const std::vector<float>& profile = result.profiles[rank];
    if (!result.whole_take && !profile.empty()) {
      AppendWindowProfile(profile, match.first_word, lo, hi, &html);
    }
    html += "</div>\n";
  }
  html += "</section>\n" + HtmlPageEnd();
  return html;
}

Status WriteSearchHtml(const std::string& path, const SearchResult& result,
                       const FrameFileReader& reader, const SearchPageInfo& info) {
  MOTIF_ASSIGN_OR_RETURN(std::string html, SearchHtmlText(result, reader, info));
  return AtomicWriteFile(path, html);
}

namespace {

// A colour class per group and per label (the map's dots, the swatches).
std::string ClassifyPageCss(const TakeClassification& r) {
  std::string css = kWordsCss;
  for (uint32_t id = 0; id < std::max<size_t>(r.group_count, r.label_names.size()); ++id) {
    css +=
        ".c" + std::to_string(id) + "{color:" + HtmlColour(id) + ";fill:" + HtmlColour(id) + "}\n";
  }
  return css;
}

void AppendClassifyOverview(const TakeClassification& r, const std::string& archive,
                            std::string* html) {
  const bool labelled = !r.label_names.empty();
  *html += "<section id=\"overview\"><h2>Overview</h2><table class=\"kv\">";
  *html += HtmlRow("archive", "<code>" + HtmlEscape(archive) + "</code>");
  const std::string distance_text =
      r.distance == "emd"      ? "Earth Mover's Distance between TF-IDF motion signatures"
      : r.distance == "emd-tf" ? "Earth Mover's Distance between signatures without TF-IDF"
                               : "dynamic time warping over the takes' frames";
  *html += HtmlRow("distance", HtmlEscape(r.distance) + ": " + distance_text + " (" +
                                   HtmlNumber("%.2f s", r.seconds_distances) + ")");
  *html += HtmlRow("takes", WithCommas(r.names.size()) +
                                (labelled ? ", " + WithCommas(r.knn.labelled) + " labelled with " +
                                                std::to_string(r.label_names.size()) + " labels"
                                          : std::string()));
  std::string unsupervised = "classical MDS into " + std::to_string(r.mds.coordinates.cols()) +
                             " dimensions, then k-means into " + std::to_string(r.group_count) +
                             " groups";
  if (labelled) {
    unsupervised += "; against the labels: adjusted Rand index " +
                    HtmlNumber("%.3f", r.adjusted_rand_index) + ", purity " +
                    HtmlNumber("%.3f", r.purity);
  }
  *html += HtmlRow("unsupervised", unsupervised);
  if (labelled) {
    *html += HtmlRow("supervised", std::to_string(r.knn.k) +
                                       "-nearest-neighbour, leave one out: "
                                       "accuracy <b>" +
                                       HtmlNumber("%.3f", r.knn.accuracy) + "</b> (" +
                                       WithCommas(r.knn.correct) + " of " +
                                       WithCommas(r.knn.labelled) + ")");
    *html += HtmlRow("retrieval", "whole-take precision@" + std::to_string(r.top) + " <b>" +
                                      HtmlNumber("%.3f", r.precision_at_top) + "</b>");
  }
  *html += "</table></section>\n";
}

// The takes at their first two MDS coordinates (the second is 0 with one dimension), scaled
// into a square of `size` pixels with a 12-pixel margin.
class MdsMapDrawer {
 public:
  explicit MdsMapDrawer(const TakeClassification& r) : r_(r) {
    const size_t n = r.names.size();
    if (n == 0) return;
    min_x_ = max_x_ = X(0);
    min_y_ = max_y_ = Y(0);
    for (size_t take = 0; take < n; ++take) {
      min_x_ = std::min(min_x_, X(take));
      max_x_ = std::max(max_x_, X(take));
      min_y_ = std::min(min_y_, Y(take));
      max_y_ = std::max(max_y_, Y(take));
    }
  }

  // One dot per take, coloured by its group or by its label (grey when unlabelled).
  std::string Svg(bool by_label) const {
    std::string svg = "<svg class=\"map\" width=\"" + HtmlNumber("%.0f", kSize) + "\" height=\"" +
                      HtmlNumber("%.0f", kSize) + "\">";
    for (size_t take = 0; take < r_.names.size(); ++take) {
      const double x = X(take);
      const double y = Y(take);
      const double px =
          12 + (kSize - 24) * (max_x_ > min_x_ ? (x - min_x_) / (max_x_ - min_x_) : 0.5);
      const double py =
          12 + (kSize - 24) * (max_y_ > min_y_ ? (max_y_ - y) / (max_y_ - min_y_) : 0.5);
      const uint32_t label = r_.labels[take];
      const std::string cls = by_label ? (label == kUnlabelled ? "" : "c" + std::to_string(label))
                                       : "c" + std::to_string(r_.groups[take]);
      svg += "<circle class=\"" + cls + "\" cx=\"" + HtmlNumber("%.1f", px) + "\" cy=\"" +
             HtmlNumber("%.1f", py) + "\" r=\"5\"" +
             (by_label && label == kUnlabelled ? " fill=\"#999\"" : "") + "><title>" +
             HtmlEscape(r_.names[take]) +
             (label == kUnlabelled ? "" : " (" + HtmlEscape(r_.label_names[label]) + ")") +
             ", group " + std::to_string(r_.groups[take]) + "</title></circle>";
    }
    return svg + "</svg>";
  }

 private:
  static constexpr double kSize = 420;

  double X(size_t take) const { return r_.mds.coordinates(static_cast<Eigen::Index>(take), 0); }
  double Y(size_t take) const {
    return r_.mds.coordinates.cols() > 1 ? r_.mds.coordinates(static_cast<Eigen::Index>(take), 1)
                                         : 0.0;
  }

  const TakeClassification& r_;
  double min_x_ = 0, max_x_ = 1, min_y_ = 0, max_y_ = 1;
};

// The MDS map by group, and by label beside it with the labels' legend when there are labels.
void AppendClassifyMaps(const TakeClassification& r, std::string* html) {
  const bool labelled = !r.label_names.empty();
  *html +=
      "<section id=\"map\"><h2>MDS map</h2><p class=\"note\">The takes at their first two "
      "MDS coordinates; hover for the clip. Left: coloured by unsupervised group";
  *html += labelled ? "; right: by label.</p>" : ".</p>";
  const MdsMapDrawer drawer(r);
  *html += drawer.Svg(false);
  if (labelled) {
    *html += " " + drawer.Svg(true) + "<p>";
    for (size_t label = 0; label < r.label_names.size(); ++label) {
      *html += "<span class=\"sw c" + std::to_string(label) + "\"></span>" +
               HtmlEscape(r.label_names[label]) + " &nbsp; ";
    }
    *html += "</p>";
  }
  *html += "</section>\n";
}

// Label against the kNN prediction (only with labels).
void AppendClassifyConfusion(const TakeClassification& r, std::string* html) {
  *html +=
      "<section id=\"confusion\"><h2>Confusion matrix</h2><p class=\"note\">Rows: the "
      "label; columns: the " +
      std::to_string(r.knn.k) +
      "-NN prediction with the take left out.</p><table class=\"g\"><tr><th></th>";
  for (const std::string& name : r.label_names) *html += "<th>" + HtmlEscape(name) + "</th>";
  *html += "</tr>";
  for (size_t truth = 0; truth < r.label_names.size(); ++truth) {
    *html += "<tr><th>" + HtmlEscape(r.label_names[truth]) + "</th>";
    for (size_t predicted = 0; predicted < r.label_names.size(); ++predicted) {
      const uint64_t count = r.knn.confusion[truth][predicted];
      *html += std::string("<td") + (truth == predicted && count ? " class=\"ok\"" : "") + ">" +
               (count ? std::to_string(count) : "") + "</td>";
    }
    *html += "</tr>";
  }
  *html += "</table></section>\n";
}

// The takes ordered by label, then group (stable: the archive's order within a pair).
std::vector<uint32_t> TakesByLabelThenGroup(const TakeClassification& r) {
  std::vector<uint32_t> order(r.names.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return std::make_pair(r.labels[a], r.groups[a]) < std::make_pair(r.labels[b], r.groups[b]);
  });
  return order;
}

// One grey cell per pair of takes, in `order`; not drawn above 400 takes (160,000 cells).
void AppendClassifyDistanceMatrix(const TakeClassification& r, const std::vector<uint32_t>& order,
                                  std::string* html) {
  const size_t n = r.names.size();
  *html += "<section id=\"matrix\"><h2>Distance matrix</h2>";
  if (n <= 400) {
    double hi = 0;
    for (Eigen::Index idx = 0; idx < r.distances.size(); ++idx)
      hi = std::max(hi, r.distances.data()[idx]);
    *html +=
        "<p class=\"note\">Takes ordered by label, then group; darker is closer.</p>"
        "<svg class=\"dm\" width=\"" +
        std::to_string(std::max<size_t>(n * 4, 200)) + "\" height=\"" +
        std::to_string(std::max<size_t>(n * 4, 200)) + "\" viewBox=\"0 0 " + std::to_string(n) +
        " " + std::to_string(n) + "\">";
    for (size_t row = 0; row < n; ++row) {
      for (size_t col = 0; col < n; ++col) {
        const double value = r.distances(order[row], order[col]);
        *html += "<rect x=\"" + std::to_string(col) + "\" y=\"" + std::to_string(row) +
                 "\" width=\"1\" height=\"1\" fill=\"" + Shade(value, 0, hi) + "\"/>";
      }
    }
    *html += "</svg>";
  } else {
    *html +=
        "<p class=\"note\">Not drawn above 400 takes (classify.json has the nearest takes "
        "of each).</p>";
  }
  *html += "</section>\n";
}

// One row: clip, label, group, the prediction (with labels; a cross when wrong), nearest takes.
void AppendClassifyTakeRow(const TakeClassification& r, uint32_t take, std::string* html) {
  const uint32_t label = r.labels[take];
  *html += "<tr><td>" + HtmlEscape(r.names[take]) + "</td><td>" +
           (label == kUnlabelled ? "" : HtmlEscape(r.label_names[label])) +
           "</td><td><span "
           "class=\"sw c" +
           std::to_string(r.groups[take]) + "\"></span>" + std::to_string(r.groups[take]) + "</td>";
  if (!r.label_names.empty()) {
    const uint32_t predicted = r.knn.predicted[take];
    *html += "<td>" +
             (predicted == kUnlabelled ? std::string() : HtmlEscape(r.label_names[predicted])) +
             (predicted != kUnlabelled && predicted != label ? " &#10007;" : "") + "</td>";
  }
  *html += "<td>";
  for (size_t idx = 0; idx < r.nearest[take].size(); ++idx) {
    const uint32_t other = r.nearest[take][idx];
    *html += (idx ? ", " : "") + HtmlEscape(r.names[other]) + " (" +
             HtmlNumber("%.3f", r.distances(take, other)) + ")";
  }
  *html += "</td></tr>";
}

void AppendClassifyTakes(const TakeClassification& r, const std::vector<uint32_t>& order,
                         std::string* html) {
  const bool labelled = !r.label_names.empty();
  *html +=
      "<section id=\"takes\"><h2>Takes</h2><table class=\"l\"><tr><th>clip</th><th>label"
      "</th><th>group</th>" +
      std::string(labelled ? "<th>predicted</th>" : "") + "<th>nearest takes (distance)</th></tr>";
  for (uint32_t take : order) AppendClassifyTakeRow(r, take, html);
  *html += "</table></section>\n";
}

}  // namespace

std::string ClassificationHtmlText(const TakeClassification& r, const std::string& archive) {
  const bool labelled = !r.label_names.empty();
  std::string html = HtmlPageStart("motifmine classify: " + archive, ClassifyPageCss(r));
  html +=
      "<h1>motifmine classify</h1>\n<nav><a href=\"#overview\">overview</a><a "
      "href=\"#map\">map</a>" +
      std::string(labelled ? "<a href=\"#confusion\">confusion</a>" : "") +
      "<a href=\"#matrix\">distances</a><a href=\"#takes\">takes</a></nav>\n";
  AppendClassifyOverview(r, archive, &html);
  AppendClassifyMaps(r, &html);
  if (labelled) AppendClassifyConfusion(r, &html);
  const std::vector<uint32_t> order = TakesByLabelThenGroup(r);
  AppendClassifyDistanceMatrix(r, order, &html);
  AppendClassifyTakes(r, order, &html);
  html += HtmlPageEnd();
  return html;
}

Status WriteClassificationHtml(const std::string& path, const TakeClassification& result,
                               const std::string& archive) {
  return AtomicWriteFile(path, ClassificationHtmlText(result, archive));
}

}  // namespace motif
