// Scores a segmentation (segments.json: a group for every frame of the takes segmented) against
// per-frame action labels, as the temporal-segmentation literature scores unsupervised methods
// (`motifmine score SEGMENTS.json TRUTH.tsv`, docs/guide.md). The labels are runs of frames in
// the annotation TSV (motif_truth.h: clip, movement = the label, start, end). Two rules give a
// group the label it is scored as:
//  * majority: every group takes the label most of its frames have (ties: the label first in
//    byte order), so several groups may take one label;
//  * one-to-one: groups and labels pair up so that the most frames agree (the Hungarian method,
//    label_assignment.h); a group left without a label scores none of its frames.
// Under each rule: frame accuracy = frames whose group's label is theirs / labelled frames; macro
// F1 = the mean over the labels of 2 TP / (frames scored as the label + frames of the label).
// Only labelled frames of segmented takes are scored; a labelled frame no segment covers counts
// as wrong. Labels in takes that were not segmented are left out and counted.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/status.h"
#include "engine/evaluation/motif_truth.h"

namespace motif {

// A stretch of a take and the group it was given (empty: none).
struct GroupedSegment {
  std::string clip;
  uint64_t start = 0;
  uint64_t end = 0;  // exclusive
  std::string group;
};

struct FrameRuleScore {
  double accuracy = 0;
  double macro_f1 = 0;
  std::vector<std::string> label_of_group;  // per group (as in FrameLabelScore::groups); "" none
};

struct ClipFrameScore {
  std::string clip;
  uint64_t frames = 0;  // labelled frames scored
  double majority_accuracy = 0;
  double one_to_one_accuracy = 0;
};

struct FrameLabelScore {
  uint64_t frames = 0;             // labelled frames scored
  uint64_t frames_ungrouped = 0;   // of those, frames no segment (or a segment without group) covers
  uint64_t frames_elsewhere = 0;   // labelled frames of takes not segmented (left out)
  std::vector<std::string> labels; // the labels scored, in byte order
  std::vector<std::string> groups; // the groups, by first appearance
  FrameRuleScore majority;
  FrameRuleScore one_to_one;
  std::vector<ClipFrameScore> clips;  // the segmented takes with labels, by first appearance
};

// InvalidArgument when one frame carries two different labels (naming the clip and frame).
Result<FrameLabelScore> ScoreFrameLabels(const std::vector<GroupedSegment>& segments,
                                         const std::vector<TruthOccurrence>& labels);

// Reads a segments.json (docs/formats/segments_json.md): its segments with their labels as
// groups. NotFound / IOError; InvalidArgument naming the path when it is not one.
Result<std::vector<GroupedSegment>> ReadSegmentsJson(const std::string& path);

}  // namespace motif
