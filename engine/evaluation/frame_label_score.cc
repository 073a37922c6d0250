#include "engine/evaluation/frame_label_score.h"

#include <algorithm>
#include <map>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "common/file_util.h"
#include "engine/evaluation/label_assignment.h"

namespace motif {

namespace {

constexpr int32_t kNone = -1;

// Index of `name` in `names`, appended when new.
int32_t IndexOf(std::vector<std::string>& names, std::map<std::string, int32_t>& index,
                const std::string& name) {
  auto [it, inserted] = index.try_emplace(name, static_cast<int32_t>(names.size()));
  if (inserted) names.push_back(name);
  return it->second;
}

struct LabelledClipFrames {
  std::vector<int32_t> label;  // per frame: label index or kNone
  std::vector<int32_t> group;  // per frame: group index or kNone
};

// The agreement table: frames of group g (rows, plus a last row for "no group") with label l.
struct Contingency {
  Eigen::MatrixXd counts;
  std::vector<uint64_t> label_frames;
};

void Resize(LabelledClipFrames& frames, uint64_t end) {
  if (frames.label.size() < end) {
    frames.label.resize(end, kNone);
    frames.group.resize(end, kNone);
  }
}

Status AddLabels(const std::vector<TruthOccurrence>& labels,
                 const std::vector<std::string>& label_names,
                 std::map<std::string, LabelledClipFrames>& clips) {
  for (const TruthOccurrence& run : labels) {
    auto clip = clips.find(run.clip);
    if (clip == clips.end()) continue;
    const int32_t label = static_cast<int32_t>(
        std::lower_bound(label_names.begin(), label_names.end(), run.movement) -
        label_names.begin());
    Resize(clip->second, run.end);
    for (uint64_t frame = run.start; frame < run.end; ++frame) {
      int32_t& slot = clip->second.label[frame];
      if (slot != kNone && slot != label) {
        return Status::InvalidArgument("frame " + std::to_string(frame) + " of clip " + run.clip +
                                       " carries two labels: " + label_names[slot] + " and " +
                                       run.movement);
      }
      slot = label;
    }
  }
  return Status::Ok();
}

// Accuracy and macro F1 when group g is scored as label_of_group[g] (kNone: no label).
FrameRuleScore RuleScore(const Contingency& table, const std::vector<int32_t>& label_of_group,
                         const std::vector<std::string>& label_names, uint64_t frames) {
  const Eigen::Index labels = table.counts.cols();
  std::vector<double> true_positive(labels, 0), predicted(labels, 0);
  FrameRuleScore score;
  for (size_t group = 0; group < label_of_group.size(); ++group) {
    const int32_t label = label_of_group[group];
    score.label_of_group.push_back(label == kNone ? "" : label_names[label]);
    if (label == kNone) continue;
    true_positive[label] += table.counts(group, label);
    predicted[label] += table.counts.row(group).sum();
  }
  double correct = 0, f1_sum = 0;
  for (Eigen::Index label = 0; label < labels; ++label) {
    correct += true_positive[label];
    const double denominator = predicted[label] + static_cast<double>(table.label_frames[label]);
    if (denominator > 0) f1_sum += 2 * true_positive[label] / denominator;
  }
  score.accuracy = frames > 0 ? correct / static_cast<double>(frames) : 0;
  score.macro_f1 = labels > 0 ? f1_sum / static_cast<double>(labels) : 0;
  return score;
}

std::vector<int32_t> MajorityLabels(const Eigen::MatrixXd& counts, size_t groups) {
  std::vector<int32_t> label_of_group(groups, kNone);
  for (size_t group = 0; group < groups; ++group) {
    Eigen::Index best = 0;
    if (counts.cols() == 0 || counts.row(group).maxCoeff(&best) <= 0) continue;
    label_of_group[group] = static_cast<int32_t>(best);  // maxCoeff keeps the first of equals
  }
  return label_of_group;
}

Contingency Tabulate(const std::map<std::string, LabelledClipFrames>& clips, size_t groups,
                     size_t labels, const std::string* only_clip) {
  Contingency table{Eigen::MatrixXd::Zero(groups + 1, labels), std::vector<uint64_t>(labels, 0)};
  for (const auto& [name, frames] : clips) {
    if (only_clip != nullptr && name != *only_clip) continue;
    for (size_t frame = 0; frame < frames.label.size(); ++frame) {
      const int32_t label = frames.label[frame];
      if (label == kNone) continue;
      const int32_t group = frames.group[frame];
      table.counts(group == kNone ? groups : group, label) += 1;
      ++table.label_frames[label];
    }
  }
  return table;
}

uint64_t LabelledFrames(const Contingency& table) {
  uint64_t frames = 0;
  for (uint64_t count : table.label_frames) frames += count;
  return frames;
}

}  // namespace

Result<FrameLabelScore> ScoreFrameLabels(const std::vector<GroupedSegment>& segments,
                                         const std::vector<TruthOccurrence>& labels) {
  FrameLabelScore score;
  std::map<std::string, int32_t> group_index;
  std::map<std::string, LabelledClipFrames> clips;
  std::vector<std::string> clip_order;
  for (const GroupedSegment& segment : segments) {
    auto [clip, inserted] = clips.try_emplace(segment.clip);
    if (inserted) clip_order.push_back(segment.clip);
    Resize(clip->second, segment.end);
    const int32_t group =
        segment.group.empty() ? kNone : IndexOf(score.groups, group_index, segment.group);
    std::fill(clip->second.group.begin() + segment.start,
              clip->second.group.begin() + segment.end, group);
  }
  for (const TruthOccurrence& run : labels) {
    if (clips.count(run.clip)) {
      score.labels.push_back(run.movement);
    } else {
      score.frames_elsewhere += run.end - run.start;
    }
  }
  std::sort(score.labels.begin(), score.labels.end());
  score.labels.erase(std::unique(score.labels.begin(), score.labels.end()), score.labels.end());
  MOTIF_RETURN_IF_ERROR(AddLabels(labels, score.labels, clips));

  const size_t groups = score.groups.size();
  const Contingency table = Tabulate(clips, groups, score.labels.size(), nullptr);
  score.frames = LabelledFrames(table);
  score.frames_ungrouped = static_cast<uint64_t>(table.counts.row(groups).sum());
  const Eigen::MatrixXd grouped = table.counts.topRows(groups);
  const std::vector<int32_t> majority = MajorityLabels(grouped, groups);
  const std::vector<int32_t> one_to_one = MaximumAgreementAssignment(grouped);
  score.majority = RuleScore(table, majority, score.labels, score.frames);
  score.one_to_one = RuleScore(table, one_to_one, score.labels, score.frames);
  for (const std::string& clip : clip_order) {
    const Contingency own = Tabulate(clips, groups, score.labels.size(), &clip);
    const uint64_t frames = LabelledFrames(own);
    if (frames == 0) continue;
    score.clips.push_back({clip, frames, RuleScore(own, majority, score.labels, frames).accuracy,
                           RuleScore(own, one_to_one, score.labels, frames).accuracy});
  }
  return score;
}

Result<std::vector<GroupedSegment>> ReadSegmentsJson(const std::string& path) {
  MOTIF_ASSIGN_OR_RETURN(std::string text, ReadFileToString(path));
  const nlohmann::json root = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (!root.is_object() || !root.contains("segments") || !root["segments"].is_array()) {
    return Status::InvalidArgument(path + ": not a segments.json (no \"segments\" array)");
  }
  std::vector<GroupedSegment> segments;
  for (const nlohmann::json& item : root["segments"]) {
    const bool valid = item.is_object() && item.value("clip", nlohmann::json()).is_string() &&
                       item.value("start", nlohmann::json()).is_number_unsigned() &&
                       item.value("end", nlohmann::json()).is_number_unsigned();
    if (!valid || item["end"].get<uint64_t>() < item["start"].get<uint64_t>()) {
      return Status::InvalidArgument(path + ": segment " + std::to_string(segments.size()) +
                                     " lacks a clip, a start or an end at or after it");
    }
    const nlohmann::json label = item.value("label", nlohmann::json());
    segments.push_back({item["clip"].get<std::string>(), item["start"].get<uint64_t>(),
                        item["end"].get<uint64_t>(),
                        label.is_string() ? label.get<std::string>() : std::string()});
  }
  return segments;
}

}  // namespace motif
