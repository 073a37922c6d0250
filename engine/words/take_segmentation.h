// Temporal segmentation of takes by motion signatures (Aristidou et al. 2018, "Temporal Motion
// Segmentation"), as `motifmine segment` does it (docs/design/signatures.md, "Segmentation"):
//  * supervised: every word of a take to segment is described by the window of `window` (9)
//    words centred on it (window_vote.h) and takes the majority label of its k (5) nearest
//    windows among those of the labelled takes, a take never voting for itself; the distance is
//    the EMD between the windows' signatures: by default their bags of words (word_bags.h, every
//    word its own bin, the DTW between words as ground distance), or the paper's TF-IDF
//    histograms over the motifs (tf_idf.h, the archive's idf); or, for the baseline, DTW over the
//    windows' frames (take_dtw.h, every `dtw_step`-th frame);
//  * unsupervised: boundaries where the signatures before and after differ most, segments
//    grouped by signature (signature_change.h); by default the words' affinity profiles
//    (affinity_profiles.h, nothing trained, so no seed), or the motifs' TF-IDF;
// then equal neighbouring labels merge into segments covering each take (MergeLabels).
// Takes shorter than one word cannot be segmented and are listed as skipped.
// Thread-safety: pure functions (the reader's and the features' const methods are thread-safe);
// the result does not depend on the thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/status.h"
#include "engine/distance/pose_features.h"
#include "engine/signature/earth_movers_distance.h"
#include "engine/words/window_vote.h"
#include "engine/words/word_model.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

// What a window's signature is made of (with the EMD).
enum class WindowSignature {
  kWords,   // every word its own bin, unit mass; ground: the DTW between words (word_bags.h)
  kMotifs,  // the paper's: TF-IDF over the motifs; ground: the centroids' distance (tf_idf.h)
};

// "words" or "motifs".
const char* WindowSignatureName(WindowSignature signature);

struct SegmentOptions {
  uint32_t window = 9;        // words per window
  uint32_t knn = 5;           // supervised: neighbours of the vote
  uint32_t dtw_step = 4;      // the DTW baseline: every n-th frame of a window
  bool one_per_take = false;  // supervised: vote with the k nearest takes (window_vote.h)
  WindowSignature signature = WindowSignature::kWords;  // with the EMD
  // Unsupervised: the number of groups (0: chosen by the change threshold, signature_change.h).
  uint32_t groups = 0;
  // Word bags: the per-joint weights the words are cut with (LoadDistanceWeights, one per archive
  // joint); empty: the skeleton's defaults.
  std::vector<float> joint_weights;
  int threads = 0;  // 0: all cores
  // (stage, done, total): "windows" (signatures, counted in takes), "vote" (queries), "groups".
  std::function<void(const std::string&, uint64_t, uint64_t)> progress;
};

struct SegmentedTake {
  uint32_t clip = 0;
  uint64_t words = 0;
  std::vector<uint32_t> word_labels;  // per word: index into label_names (kUnlabelled: none)
  std::vector<LabelledSegment> segments;
  std::vector<double> change_scores;  // unsupervised: per word boundary (signature_change.h)
};

struct Segmentation {
  bool supervised = false;
  std::string distance;                  // "emd", "dtw" or (affinity profiles) "euclidean"
  std::string linkage;                   // unsupervised: "complete" or "average"
  std::string signature;                 // with the EMD: "words" or "motifs"
  std::vector<std::string> label_names;  // supervised: the labels, sorted; else "group 1", ...
  std::vector<SegmentedTake> takes;      // in the order asked for
  std::vector<uint32_t> skipped_clips;   // asked for, but shorter than one word
  uint64_t reference_windows = 0;        // supervised: windows of the labelled takes
  uint64_t reference_takes = 0;
  double threshold = 0;        // unsupervised: the change threshold
  double group_threshold = 0;  // unsupervised: segments within it join a group
  uint32_t window = 9;
  uint32_t knn = 5;
  bool one_per_take = false;  // supervised: the neighbours are takes (window_vote.h)
};

// `clip_labels[c]` per archive clip: its label index (< label_names.size()) or kUnlabelled.
// `features`: null for the EMD; the archive's pose features for the DTW baseline.
// InvalidArgument: no labelled take with words, bad options, a clip out of range.
Result<Segmentation> SegmentSupervised(const FrameFileReader& reader, const LoadedWords& words,
                                       const std::vector<uint32_t>& clips,
                                       const std::vector<uint32_t>& clip_labels,
                                       const std::vector<std::string>& label_names,
                                       const PoseFeatures* features, const SegmentOptions& options);

// InvalidArgument: bad options, a clip out of range.
Result<Segmentation> SegmentUnsupervised(const FrameFileReader& reader, const LoadedWords& words,
                                         const std::vector<uint32_t>& clips,
                                         const SegmentOptions& options);

// The change scores of clip `clip` (signature_change.h: the EMD between the TF-IDF signatures of
// the `window` words before and after each word boundary). Errors of the EMD pass through.
Result<std::vector<double>> TakeChangeScores(const LoadedWords& words, uint32_t clip,
                                             uint32_t window, EarthMoversDistance& emd);

// The clip frame at the centre of each word of `clip`.
std::vector<double> WordCentres(const FrameFileReader& reader, const LoadedWords& words,
                                uint32_t clip);

// A segment of a group (a label): clip frames [start, end).
struct GroupMember {
  uint32_t clip = 0;
  uint64_t start = 0;
  uint64_t end = 0;
};

// Per label, the segments that carry it, take by take in the result's order.
std::vector<std::vector<GroupMember>> GroupMembers(const Segmentation& result);

// segments.json (docs/formats/segments_json.md).
nlohmann::json SegmentsJson(const Segmentation& result, const FrameFileReader& reader,
                            const std::string& archive);

}  // namespace motif
