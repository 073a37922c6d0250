// motifmine score MOTIFS.json TRUTH [--json]: how well mined motifs match ground truth, for users
// with their own annotations (engine/evaluation/truth_score.h: the hit rule and the figures);
// motifmine score SEGMENTS.json LABELS.tsv: a segmentation against per-frame labels
// (engine/evaluation/frame_label_score.h: the majority and one-to-one rules).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "engine/cli/cli_common.h"
#include "engine/evaluation/frame_label_score.h"
#include "engine/evaluation/truth_score.h"

namespace motif::cli {

namespace po = boost::program_options;

namespace {

nlohmann::json MatchJson(const MotifMovementMatch& match) {
  return {{"motif", match.motif},
          {"movement", match.movement},
          {"instances", match.instances},
          {"instances_hitting", match.instances_hitting},
          {"occurrences", match.occurrences},
          {"occurrences_hit", match.occurrences_hit},
          {"precision", match.precision},
          {"recall", match.recall},
          {"f1", match.f1}};
}

nlohmann::json ScoreJson(const TruthScore& score) {
  nlohmann::json json = {{"hit_iou", kTruthHitIoU},
                         {"occurrences", score.occurrences},
                         {"occurrences_elsewhere", score.occurrences_elsewhere},
                         {"movements", score.movements},
                         {"motifs", score.motifs},
                         {"instances", score.instances},
                         {"occurrences_hit", score.occurrences_hit},
                         {"instances_hitting", score.instances_hitting},
                         {"recall", score.recall},
                         {"precision", score.precision},
                         {"top1", MatchJson(score.top1)}};
  json["top1_phase_free"] = MatchJson(score.top1_phase_free);
  json["top1_phase_free"]["back_to_back"] = score.top1_phase_free.back_to_back;
  json["top1_phase_free"]["shift"] = score.top1_phase_free.shift;
  json["per_motif"] = nlohmann::json::array();
  for (const MotifMovementMatch& match : score.per_motif) {
    json["per_motif"].push_back(MatchJson(match));
  }
  json["per_movement"] = nlohmann::json::array();
  for (const MotifMovementMatch& match : score.per_movement) {
    json["per_movement"].push_back(MatchJson(match));
  }
  return json;
}

std::string MotifName(const MotifMovementMatch& match) {
  return match.motif < 0 ? std::string("none") : "motif " + std::to_string(match.motif);
}

void PrintScore(const TruthScore& score, const std::string& motifs_path,
                const std::string& truth_path, uint32_t motifs_shown) {
  std::printf("motifmine score: %s against %s (a hit: same clip, IoU >= %.1f)\n",
              motifs_path.c_str(), truth_path.c_str(), kTruthHitIoU);
  std::printf("  truth        %s occurrences of %s movements",
              WithCommas(score.occurrences).c_str(), WithCommas(score.movements).c_str());
  if (score.occurrences_elsewhere > 0) {
    std::printf(" (%s more in clips not mined, left out)",
                WithCommas(score.occurrences_elsewhere).c_str());
  }
  std::printf("\n  found        %s motifs, %s instances\n", WithCommas(score.motifs).c_str(),
              WithCommas(score.instances).c_str());
  std::printf(
      "  all motifs   recall %.3f (%s of %s occurrences hit), precision %.3f (%s of %s "
      "instances hit one)\n",
      score.recall, WithCommas(score.occurrences_hit).c_str(),
      WithCommas(score.occurrences).c_str(), score.precision,
      WithCommas(score.instances_hitting).c_str(), WithCommas(score.instances).c_str());
  const MotifMovementMatch& top = score.top1;
  std::printf("  top motif    %s (%s instances) ~ %s: precision %.3f recall %.3f\n",
              MotifName(top).c_str(), WithCommas(top.instances).c_str(),
              top.movement.empty() ? "no movement" : top.movement.c_str(), top.precision,
              top.recall);
  const MotifMovementMatch& free = score.top1_phase_free;
  std::printf("  phase free   %s ~ %s: precision %.3f recall %.3f", MotifName(free).c_str(),
              free.movement.empty() ? "no movement" : free.movement.c_str(), free.precision,
              free.recall);
  if (free.back_to_back) {
    std::printf(" (back to back; instances shifted %+lld frames)",
                static_cast<long long>(free.shift));
  }
  std::printf("\n  movements    best motif per movement:\n");
  for (const MotifMovementMatch& match : score.per_movement) {
    std::printf("    %-28s %4llu occurrences  %-10s precision %.3f recall %.3f f1 %.3f\n",
                match.movement.c_str(), static_cast<unsigned long long>(match.occurrences),
                MotifName(match).c_str(), match.precision, match.recall, match.f1);
  }
  const size_t shown = std::min<size_t>(motifs_shown, score.per_motif.size());
  if (shown > 0) std::printf("  motifs       the first %zu, each against its movement:\n", shown);
  for (size_t rank = 0; rank < shown; ++rank) {
    const MotifMovementMatch& match = score.per_motif[rank];
    std::printf("    %-10s %4llu instances  %-28s precision %.3f recall %.3f f1 %.3f\n",
                MotifName(match).c_str(), static_cast<unsigned long long>(match.instances),
                match.movement.empty() ? "-" : match.movement.c_str(), match.precision,
                match.recall, match.f1);
  }
}

nlohmann::json RuleJson(const FrameRuleScore& rule) {
  return {{"accuracy", rule.accuracy},
          {"macro_f1", rule.macro_f1},
          {"label_of_group", rule.label_of_group}};
}

nlohmann::json FrameScoreJson(const FrameLabelScore& score) {
  nlohmann::json json = {{"frames", score.frames},
                         {"frames_ungrouped", score.frames_ungrouped},
                         {"frames_elsewhere", score.frames_elsewhere},
                         {"labels", score.labels},
                         {"groups", score.groups},
                         {"majority", RuleJson(score.majority)},
                         {"one_to_one", RuleJson(score.one_to_one)},
                         {"clips", nlohmann::json::array()}};
  for (const ClipFrameScore& clip : score.clips) {
    json["clips"].push_back({{"clip", clip.clip},
                             {"frames", clip.frames},
                             {"majority_accuracy", clip.majority_accuracy},
                             {"one_to_one_accuracy", clip.one_to_one_accuracy}});
  }
  return json;
}

void PrintFrameScore(const FrameLabelScore& score, const std::string& segments_path,
                     const std::string& truth_path) {
  std::printf("motifmine score: %s against the per-frame labels of %s\n", segments_path.c_str(),
              truth_path.c_str());
  std::printf("  truth        %s labelled frames, %s labels", WithCommas(score.frames).c_str(),
              WithCommas(score.labels.size()).c_str());
  if (score.frames_elsewhere > 0) {
    std::printf(" (%s more in takes not segmented, left out)",
                WithCommas(score.frames_elsewhere).c_str());
  }
  std::printf("\n  found        %s groups; %s labelled frames without a group\n",
              WithCommas(score.groups.size()).c_str(), WithCommas(score.frames_ungrouped).c_str());
  std::printf("  majority     frame accuracy %.3f, macro F1 %.3f\n", score.majority.accuracy,
              score.majority.macro_f1);
  std::printf("  one-to-one   frame accuracy %.3f, macro F1 %.3f\n", score.one_to_one.accuracy,
              score.one_to_one.macro_f1);
  std::printf("  groups       scored as (majority / one-to-one):\n");
  for (size_t group = 0; group < score.groups.size(); ++group) {
    const std::string& paired = score.one_to_one.label_of_group[group];
    std::printf("    %-14s %s / %s\n", score.groups[group].c_str(),
                score.majority.label_of_group[group].c_str(), paired.empty() ? "-" : paired.c_str());
  }
  std::printf("  takes        frame accuracy (majority / one-to-one):\n");
  for (const ClipFrameScore& clip : score.clips) {
    std::printf("    %-14s %8s frames  %.3f / %.3f\n", clip.clip.c_str(),
                WithCommas(clip.frames).c_str(), clip.majority_accuracy, clip.one_to_one_accuracy);
  }
}

int ScoreSegments(const std::vector<GroupedSegment>& segments, const std::string& segments_path,
                  const std::string& truth_path, bool json) {
  Result<std::vector<TruthOccurrence>> labels = ReadTruthOccurrences(truth_path);
  if (!labels.ok()) return ReportError("score", labels.status());
  Result<FrameLabelScore> score = ScoreFrameLabels(segments, *labels);
  if (!score.ok()) return ReportError("score", score.status().WithContext(truth_path));
  if (json) {
    std::printf("%s\n", FrameScoreJson(*score).dump(2).c_str());
  } else {
    PrintFrameScore(*score, segments_path, truth_path);
  }
  return kExitOk;
}

}  // namespace

int RunScore(const std::vector<std::string>& args) {
  CommandSpec spec;
  spec.name = "score";
  spec.usage = "motifmine score (MOTIFS.json | SEGMENTS.json) TRUTH [--json] [--motifs N]";
  spec.summary =
      "Scores mined motifs against ground truth. TRUTH is an annotation TSV (clip, movement,\n"
      "start, end: docs/formats/repetitions_tsv.md) or a synthetic archive's truth.json. A found\n"
      "instance hits an occurrence when both are in the same clip with IoU >= 0.5. Prints recall\n"
      "and precision over all motifs, the top motif against the movement it matches best (and\n"
      "phase free: a movement done back to back scored at the best common shift of the motif's\n"
      "instances, up to half its length), the best motif of every movement and the first\n"
      "motifs against theirs.\n"
      "Given a segments.json (motifmine segment), TRUTH is per-frame labels as runs in the same\n"
      "TSV (movement = the label), and it prints the frame accuracy and macro F1 of the groups\n"
      "under the majority and the one-to-one (Hungarian) rule.";
  spec.options.add_options()("json", "print the figures as one JSON object instead")(
      "motifs", po::value<uint32_t>()->default_value(10), "motifs listed in the text output");
  spec.positional = {{"motifs-json", 1}, {"truth", 1}};
  po::variables_map vm;
  if (int code = ParseCommand(spec, args, &vm); code >= 0) return code;
  if (!vm.count("motifs-json") || !vm.count("truth")) {
    std::fprintf(stderr, "motifmine score: error: MOTIFS.json and TRUTH are required\nusage: %s\n",
                 spec.usage.c_str());
    return kExitUsage;
  }
  const std::string motifs_path = vm["motifs-json"].as<std::string>();
  const std::string truth_path = vm["truth"].as<std::string>();
  if (Result<std::vector<GroupedSegment>> segments = ReadSegmentsJson(motifs_path); segments.ok()) {
    return ScoreSegments(*segments, motifs_path, truth_path, vm.count("json") > 0);
  }
  Result<MotifsDocument> document = ReadMotifsJson(motifs_path);
  if (!document.ok()) return ReportError("score", document.status());
  Result<std::vector<TruthOccurrence>> truth = ReadTruthOccurrences(truth_path);
  if (!truth.ok()) return ReportError("score", truth.status());
  const TruthScore score = ScoreAgainstTruth(*document, *truth);
  if (vm.count("json")) {
    std::printf("%s\n", ScoreJson(score).dump(2).c_str());
  } else {
    PrintScore(score, motifs_path, truth_path, vm["motifs"].as<uint32_t>());
  }
  return kExitOk;
}

}  // namespace motif::cli
