#include "engine/words/take_segmentation.h"

#include <memory>
#include <set>
#include <span>

#include "engine/signature/earth_movers_distance.h"
#include "engine/signature/frame_resampler.h"
#include "engine/signature/take_dtw.h"
#include "engine/signature/take_retrieval.h"
#include "engine/signature/word_stream.h"
#include "engine/words/affinity_profiles.h"
#include "engine/words/signature_change.h"
#include "engine/words/word_bags.h"

namespace motif {
namespace {

// A window of words of one clip: [first, end).
using Window = WordRange;

Status CheckOptions(const FrameFileReader& reader, const std::vector<uint32_t>& clips,
                    const SegmentOptions& options) {
  if (options.window == 0) return Status::InvalidOption("window", "must be at least 1");
  if (options.knn == 0) return Status::InvalidOption("knn", "must be at least 1");
  if (options.dtw_step == 0) return Status::InvalidOption("dtw-step", "must be at least 1");
  for (uint32_t clip : clips) {
    if (clip >= reader.clips().size()) {
      return Status::InvalidArgument("segment: clip index " + std::to_string(clip) +
                                     " out of range");
    }
  }
  return Status::Ok();
}

// Every word's centred window, take by take.
std::vector<Window> CentredWindows(const LoadedWords& words, const std::vector<uint32_t>& clips,
                                   uint32_t window) {
  std::vector<Window> windows;
  for (uint32_t clip : clips) {
    const uint64_t count = words.signatures.clip_words[clip];
    for (uint64_t word = 0; word < count; ++word) {
      const auto [first, end] = CentredWindow(word, count, window);
      windows.push_back({clip, first, end});
    }
  }
  return windows;
}

Result<std::vector<std::vector<double>>> WindowSignatures(const LoadedWords& words,
                                                          const std::vector<Window>& windows) {
  std::vector<std::vector<double>> signatures;
  signatures.reserve(windows.size());
  for (const Window& window : windows) {
    MOTIF_ASSIGN_OR_RETURN(std::vector<double> signature,
                           words.RangeSignature(window.clip, window.first, window.end));
    signatures.push_back(std::move(signature));
  }
  return signatures;
}

// Archive frames [first, end) that the words of `window` read.
TakeFrames WindowFrames(const FrameFileReader& reader, const LoadedWords& words,
                        const Window& window) {
  const WordGrid grid = ClipWordGrid(reader, window.clip, words.signatures.words);
  const uint64_t base = reader.clips()[window.clip].first_frame;
  return {base + grid.SourceFrames(window.first).first,
          base + grid.SourceFrames(window.end - 1).end};
}

// Splits the labels of all query windows back into takes and merges them into segments.
void FillTakes(const FrameFileReader& reader, const LoadedWords& words,
               const std::vector<uint32_t>& clips, const std::vector<uint32_t>& labels,
               Segmentation* result) {
  size_t next = 0;
  for (uint32_t clip : clips) {
    SegmentedTake take;
    take.clip = clip;
    take.words = words.signatures.clip_words[clip];
    take.word_labels.assign(labels.begin() + static_cast<std::ptrdiff_t>(next),
                            labels.begin() + static_cast<std::ptrdiff_t>(next + take.words));
    next += take.words;
    take.segments = MergeLabels(take.word_labels, WordCentres(reader, words, clip),
                                reader.clips()[clip].frame_count);
    result->takes.push_back(std::move(take));
  }
}

// The clips asked for that have words; the others go to `skipped`.
std::vector<uint32_t> TakesWithWords(const LoadedWords& words, const std::vector<uint32_t>& clips,
                                     std::vector<uint32_t>* skipped) {
  std::vector<uint32_t> takes;
  for (uint32_t clip : clips) {
    (words.signatures.clip_words[clip] > 0 ? takes : *skipped).push_back(clip);
  }
  return takes;
}

WindowDistanceMaker EmdMaker(const std::vector<std::vector<double>>& queries,
                             const std::vector<std::vector<double>>& references,
                             const Eigen::MatrixXd& ground) {
  return [&] {
    auto emd = std::make_shared<EarthMoversDistance>();
    return WindowDistance([&, emd](size_t query, size_t reference) {
      return emd->Distance(queries[query], references[reference], ground);
    });
  };
}

WindowDistanceMaker DtwMaker(const PoseFeatures& features, const std::vector<TakeFrames>& queries,
                             const std::vector<TakeFrames>& references, uint32_t step) {
  return [&, step] {
    return WindowDistance([&, step](size_t query, size_t reference) -> Result<double> {
      return TakeDtw(features, queries[query], references[reference], step);
    });
  };
}

// How words are compared: the joint weights they are cut with (options.joint_weights, else the
// skeleton's defaults) and the DTW between words on those joints.
struct WordComparison {
  std::vector<float> weights;
  WordDistance distance;
};

Result<WordComparison> CompareWordsBy(const FrameFileReader& reader, const LoadedWords& words,
                                      const SegmentOptions& options) {
  std::vector<float> weights = options.joint_weights;
  if (weights.empty()) {
    MOTIF_ASSIGN_OR_RETURN(weights, LoadDistanceWeights(reader.skeleton(), ""));
  }
  MOTIF_ASSIGN_OR_RETURN(const FrameResampler resampler,
                         FrameResampler::Create(reader.layout(), weights));
  WordDistance distance(resampler.weights(), words.signatures.words.word_frames);
  return WordComparison{std::move(weights), std::move(distance)};
}

// Query windows per block of the word-bag vote: the block's words against every reference word
// are held as floats, (kBagQueries + window) x reference words.
constexpr size_t kBagQueries = 256;

// The vote with word bags (word_bags.h): the queries of each take a block at a time, each block
// with the DTW between the words its windows read and every word of the references.
Result<std::vector<uint32_t>> VoteWithWordBags(
    const FrameFileReader& reader, const LoadedWords& words, const std::vector<Window>& queries,
    const std::vector<Window>& references, const std::vector<uint32_t>& query_clips,
    const std::vector<uint32_t>& reference_clips, const WindowVoteInput& input,
    const SegmentOptions& options, const std::function<void(uint64_t, uint64_t)>& progress) {
  MOTIF_ASSIGN_OR_RETURN(const WordComparison comparison, CompareWordsBy(reader, words, options));
  const std::vector<float>& weights = comparison.weights;
  const WordDistance& distance = comparison.distance;
  const WordOptions& geometry = words.signatures.words;
  MOTIF_ASSIGN_OR_RETURN(const WordsOfClips reference_words,
                         WordsOfClips::Read(reader, weights, geometry, distance, reference_clips));
  // A labelled take being segmented is read once, as a reference.
  std::vector<uint32_t> unlabelled_clips;
  for (uint32_t clip : query_clips) {
    if (!reference_words.holds(clip)) unlabelled_clips.push_back(clip);
  }
  MOTIF_ASSIGN_OR_RETURN(const WordsOfClips unlabelled_words,
                         WordsOfClips::Read(reader, weights, geometry, distance, unlabelled_clips));
  std::vector<uint32_t> labels;
  for (size_t first = 0; first < queries.size();) {
    size_t end = first;
    uint64_t word_first = queries[first].first;
    uint64_t word_end = queries[first].end;
    while (end < queries.size() && end - first < kBagQueries &&
           queries[end].clip == queries[first].clip) {
      word_first = std::min(word_first, queries[end].first);
      word_end = std::max(word_end, queries[end].end);
      ++end;
    }
    const uint32_t clip = queries[first].clip;
    const WordBagGround ground = WordBagGround::Compute(
        reference_words.holds(clip) ? reference_words : unlabelled_words, clip, word_first,
        word_end, reference_words, distance, options.threads);
    WindowVoteInput block = input;
    block.query_takes.assign(input.query_takes.begin() + static_cast<std::ptrdiff_t>(first),
                             input.query_takes.begin() + static_cast<std::ptrdiff_t>(end));
    const WindowDistanceMaker make_distance = [&] {
      auto bag = std::make_shared<WordBagDistance>();
      return WindowDistance([&, bag](size_t query, size_t reference) {
        const Window& a = queries[first + query];
        const Window& b = references[reference];
        return bag->Distance(ground, a.first, a.end, reference_words, b.clip, b.first, b.end);
      });
    };
    MOTIF_ASSIGN_OR_RETURN(
        const std::vector<uint32_t> block_labels,
        VoteWindows(block, make_distance, options.threads, [&](uint64_t done, uint64_t) {
          if (progress) progress(first + done, queries.size());
        }));
    labels.insert(labels.end(), block_labels.begin(), block_labels.end());
    first = end;
  }
  return labels;
}

// How segments are cut and grouped on a kind of signature (docs/design/signatures.md): the
// change threshold is the mean plus `deviations` standard deviations of the change scores, and
// segments join groups by `linkage`.
struct UnsupervisedRule {
  double deviations = 1.0;
  Linkage linkage = Linkage::kComplete;
};

// What the unsupervised segmentation compares: change scores of a take and the distances between
// segments, on motif signatures or on affinity profiles.
class UnsupervisedSignatures {
 public:
  virtual ~UnsupervisedSignatures() = default;
  virtual UnsupervisedRule rule() const = 0;
  // The distance within which segments join a group.
  virtual double GroupThreshold(const std::vector<WordRange>& pieces,
                                double change_threshold) const = 0;
  virtual Result<std::vector<double>> ChangeScores(uint32_t clip, uint32_t window) = 0;
  virtual Result<Eigen::MatrixXd> PieceDistances(
      const std::vector<WordRange>& pieces,
      const std::function<void(uint64_t, uint64_t)>& progress) = 0;
};

// The paper's: TF-IDF signatures over the motifs, EMD between them (they depend on the seed the
// embedding was trained with).
class MotifSignatures : public UnsupervisedSignatures {
 public:
  explicit MotifSignatures(const LoadedWords& words) : words_(words) {}

  UnsupervisedRule rule() const override { return {1.0, Linkage::kComplete}; }
  // A group never holds two segments farther apart than a boundary would separate.
  double GroupThreshold(const std::vector<WordRange>&, double change_threshold) const override {
    return change_threshold;
  }

  Result<std::vector<double>> ChangeScores(uint32_t clip, uint32_t window) override {
    return TakeChangeScores(words_, clip, window, emd_);
  }

  Result<Eigen::MatrixXd> PieceDistances(
      const std::vector<WordRange>& pieces,
      const std::function<void(uint64_t, uint64_t)>& progress) override {
    MOTIF_ASSIGN_OR_RETURN(const auto signatures, WindowSignatures(words_, pieces));
    const auto n = static_cast<Eigen::Index>(pieces.size());
    Eigen::MatrixXd distances = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index a = 0; a < n; ++a) {
      for (Eigen::Index b = a + 1; b < n; ++b) {
        MOTIF_ASSIGN_OR_RETURN(const double distance,
                               emd_.Distance(signatures[static_cast<size_t>(a)],
                                             signatures[static_cast<size_t>(b)], words_.ground));
        distances(a, b) = distance;
        distances(b, a) = distance;
      }
      if (progress) progress(static_cast<uint64_t>(a + 1), pieces.size());
    }
    return distances;
  }

 private:
  const LoadedWords& words_;
  EarthMoversDistance emd_;
};

// Affinity profiles of the words (affinity_profiles.h): nothing trained, no seed.
class ProfileSignatures : public UnsupervisedSignatures {
 public:
  static Result<std::unique_ptr<UnsupervisedSignatures>> Compute(
      const FrameFileReader& reader, const LoadedWords& words, const std::vector<uint32_t>& takes,
      const SegmentOptions& options) {
    MOTIF_ASSIGN_OR_RETURN(const WordComparison comparison,
                           CompareWordsBy(reader, words, options));
    const WordDistance& distance = comparison.distance;
    MOTIF_ASSIGN_OR_RETURN(const WordsOfClips bags,
                           WordsOfClips::Read(reader, comparison.weights, words.signatures.words,
                                              distance, takes));
    auto signatures = std::make_unique<ProfileSignatures>(words);
    signatures->profiles_ = AffinityProfiles::Compute(
        bags, takes, words.signatures.clip_words, distance, options.threads,
        [&](uint64_t done, uint64_t total) {
          if (options.progress) options.progress("profiles", done, total);
        });
    return std::unique_ptr<UnsupervisedSignatures>(std::move(signatures));
  }

  explicit ProfileSignatures(const LoadedWords& words) : words_(words) {}

  // A boundary is a peak of the change score above the scores' mean; see GroupThreshold.
  UnsupervisedRule rule() const override { return {0.0, Linkage::kAverage}; }
  // Segments are one activity when they are as alike as the two halves of one segment are: the
  // mean plus half a standard deviation of the distances between the halves of every segment of
  // two words or more (the change threshold when there is none).
  double GroupThreshold(const std::vector<WordRange>& pieces,
                        double change_threshold) const override {
    std::vector<double> halves;
    for (const WordRange& piece : pieces) {
      if (piece.end - piece.first < 2) continue;
      const uint64_t middle = piece.first + (piece.end - piece.first) / 2;
      halves.push_back(profiles_.Distance({piece.clip, piece.first, middle},
                                          {piece.clip, middle, piece.end}));
    }
    return halves.empty() ? change_threshold : ChangeThreshold({halves}, 0.5);
  }

  Result<std::vector<double>> ChangeScores(uint32_t clip, uint32_t window) override {
    return ProfileChangeScores(profiles_, clip, words_.signatures.clip_words[clip], window);
  }

  Result<Eigen::MatrixXd> PieceDistances(
      const std::vector<WordRange>& pieces,
      const std::function<void(uint64_t, uint64_t)>& progress) override {
    Eigen::MatrixXd distances = ProfilePieceDistances(profiles_, pieces);
    if (progress) progress(pieces.size(), pieces.size());
    return distances;
  }

 private:
  const LoadedWords& words_;
  AffinityProfiles profiles_;
};

}  // namespace

const char* WindowSignatureName(WindowSignature signature) {
  return signature == WindowSignature::kWords ? "words" : "motifs";
}

Result<std::vector<double>> TakeChangeScores(const LoadedWords& words, uint32_t clip,
                                             uint32_t window, EarthMoversDistance& emd) {
  Status failure;
  std::vector<double> scores =
      ChangeScores(words.signatures.clip_words[clip], window,
                   [&](uint64_t a_first, uint64_t a_end, uint64_t b_first, uint64_t b_end) {
                     Result<std::vector<double>> a = words.RangeSignature(clip, a_first, a_end);
                     Result<std::vector<double>> b = words.RangeSignature(clip, b_first, b_end);
                     Result<double> distance =
                         a.ok() && b.ok() ? emd.Distance(*a, *b, words.ground)
                                          : Result<double>(a.ok() ? b.status() : a.status());
                     if (!distance.ok() && failure.ok()) failure = distance.status();
                     return distance.ok() ? *distance : 0.0;
                   });
  MOTIF_RETURN_IF_ERROR(failure);
  return scores;
}

std::vector<double> WordCentres(const FrameFileReader& reader, const LoadedWords& words,
                                uint32_t clip) {
  const WordGrid grid = ClipWordGrid(reader, clip, words.signatures.words);
  std::vector<double> centres;
  for (uint64_t word = 0; word < grid.word_count(); ++word) {
    const FrameSpan span = grid.SourceFrames(word);
    centres.push_back(static_cast<double>(span.first + span.end - 1) / 2);
  }
  return centres;
}

Result<Segmentation> SegmentSupervised(const FrameFileReader& reader, const LoadedWords& words,
                                       const std::vector<uint32_t>& clips,
                                       const std::vector<uint32_t>& clip_labels,
                                       const std::vector<std::string>& label_names,
                                       const PoseFeatures* features,
                                       const SegmentOptions& options) {
  MOTIF_RETURN_IF_ERROR(CheckOptions(reader, clips, options));
  Segmentation result;
  result.supervised = true;
  result.distance = features ? "dtw" : "emd";
  if (!features) result.signature = WindowSignatureName(options.signature);
  result.label_names = label_names;
  result.window = options.window;
  result.knn = options.knn;
  result.one_per_take = options.one_per_take;
  std::vector<uint32_t> reference_clips;
  for (uint32_t clip = 0; clip < clip_labels.size(); ++clip) {
    if (clip_labels[clip] != kUnlabelled && words.signatures.clip_words[clip] > 0) {
      reference_clips.push_back(clip);
    }
  }
  if (reference_clips.empty()) {
    return Status::InvalidArgument("segment: no labelled take has a motion word");
  }
  const std::vector<uint32_t> takes = TakesWithWords(words, clips, &result.skipped_clips);
  const std::vector<Window> queries = CentredWindows(words, takes, options.window);
  const std::vector<Window> references = CentredWindows(words, reference_clips, options.window);
  result.reference_windows = references.size();
  result.reference_takes = reference_clips.size();

  WindowVoteInput input;
  input.label_count = static_cast<uint32_t>(label_names.size());
  input.k = options.knn;
  input.take_count = static_cast<uint32_t>(reader.clips().size());
  input.one_per_take = options.one_per_take;
  for (const Window& window : queries) input.query_takes.push_back(window.clip);
  for (const Window& window : references) {
    input.reference_takes.push_back(window.clip);
    input.reference_labels.push_back(clip_labels[window.clip]);
  }
  const auto progress = [&](uint64_t done, uint64_t total) {
    if (options.progress) options.progress("vote", done, total);
  };
  Result<std::vector<uint32_t>> labels = Status::InvalidArgument("no vote");
  if (features) {
    std::vector<TakeFrames> query_frames;
    std::vector<TakeFrames> reference_frames;
    for (const Window& window : queries)
      query_frames.push_back(WindowFrames(reader, words, window));
    for (const Window& window : references) {
      reference_frames.push_back(WindowFrames(reader, words, window));
    }
    labels =
        VoteWindows(input, DtwMaker(*features, query_frames, reference_frames, options.dtw_step),
                    options.threads, progress);
  } else if (options.signature == WindowSignature::kWords) {
    labels = VoteWithWordBags(reader, words, queries, references, takes, reference_clips, input,
                              options, progress);
  } else {
    MOTIF_ASSIGN_OR_RETURN(const auto query_signatures, WindowSignatures(words, queries));
    MOTIF_ASSIGN_OR_RETURN(const auto reference_signatures, WindowSignatures(words, references));
    labels = VoteWindows(input, EmdMaker(query_signatures, reference_signatures, words.ground),
                         options.threads, progress);
  }
  if (!labels.ok()) return labels.status();
  FillTakes(reader, words, takes, *labels, &result);
  return result;
}

Result<Segmentation> SegmentUnsupervised(const FrameFileReader& reader, const LoadedWords& words,
                                         const std::vector<uint32_t>& clips,
                                         const SegmentOptions& options) {
  MOTIF_RETURN_IF_ERROR(CheckOptions(reader, clips, options));
  Segmentation result;
  result.distance = options.signature == WindowSignature::kWords ? "euclidean" : "emd";
  result.signature = WindowSignatureName(options.signature);
  result.window = options.window;
  const std::vector<uint32_t> takes = TakesWithWords(words, clips, &result.skipped_clips);
  std::unique_ptr<UnsupervisedSignatures> signatures;
  if (options.signature == WindowSignature::kWords) {
    MOTIF_ASSIGN_OR_RETURN(signatures, ProfileSignatures::Compute(reader, words, takes, options));
  } else {
    signatures = std::make_unique<MotifSignatures>(words);
  }
  std::vector<std::vector<double>> scores;
  for (uint32_t clip : takes) {
    MOTIF_ASSIGN_OR_RETURN(std::vector<double> take_scores,
                           signatures->ChangeScores(clip, options.window));
    scores.push_back(std::move(take_scores));
    if (options.progress) options.progress("windows", scores.size(), takes.size());
  }
  const UnsupervisedRule rule = signatures->rule();
  result.linkage = rule.linkage == Linkage::kAverage ? "average" : "complete";
  result.threshold = ChangeThreshold(scores, rule.deviations);

  // The segments between boundaries, then their signatures' distances.
  std::vector<WordRange> pieces;
  for (size_t take = 0; take < takes.size(); ++take) {
    uint64_t first = 0;
    for (uint64_t boundary : PickBoundaries(scores[take], result.threshold, options.window)) {
      pieces.push_back({takes[take], first, boundary});
      first = boundary;
    }
    pieces.push_back({takes[take], first, words.signatures.clip_words[takes[take]]});
  }
  result.group_threshold = signatures->GroupThreshold(pieces, result.threshold);
  MOTIF_ASSIGN_OR_RETURN(const Eigen::MatrixXd distances,
                         signatures->PieceDistances(pieces, [&](uint64_t done, uint64_t total) {
                           if (options.progress) options.progress("groups", done, total);
                         }));
  const std::vector<uint32_t> groups =
      LinkageGroups(distances, result.group_threshold, options.groups, rule.linkage);
  uint32_t group_count = 0;
  std::vector<uint32_t> labels;
  for (size_t piece = 0; piece < pieces.size(); ++piece) {
    group_count = std::max(group_count, groups[piece] + 1);
    labels.insert(labels.end(), pieces[piece].end - pieces[piece].first, groups[piece]);
  }
  for (uint32_t group = 0; group < group_count; ++group) {
    result.label_names.push_back("group " + std::to_string(group + 1));
  }
  FillTakes(reader, words, takes, labels, &result);
  for (size_t take = 0; take < takes.size(); ++take) {
    result.takes[take].change_scores = std::move(scores[take]);
  }
  return result;
}

std::vector<std::vector<GroupMember>> GroupMembers(const Segmentation& result) {
  std::vector<std::vector<GroupMember>> members(result.label_names.size());
  for (const SegmentedTake& take : result.takes) {
    for (const LabelledSegment& segment : take.segments) {
      if (segment.label == kUnlabelled) continue;
      members[segment.label].push_back({take.clip, segment.start, segment.end});
    }
  }
  return members;
}

namespace {

// Per label its segments, frames and member stretches.
nlohmann::json GroupsJson(const Segmentation& result, const FrameFileReader& reader) {
  nlohmann::json groups = nlohmann::json::array();
  const std::vector<std::vector<GroupMember>> members = GroupMembers(result);
  for (size_t label = 0; label < members.size(); ++label) {
    nlohmann::json stretches = nlohmann::json::array();
    uint64_t frames = 0;
    std::set<uint32_t> clips;
    for (const GroupMember& member : members[label]) {
      stretches.push_back({{"clip", reader.clips()[member.clip].name},
                           {"start", member.start},
                           {"end", member.end}});
      frames += member.end - member.start;
      clips.insert(member.clip);
    }
    groups.push_back({{"label", result.label_names[label]},
                      {"segments", members[label].size()},
                      {"takes", clips.size()},
                      {"frames", frames},
                      {"members", stretches}});
  }
  return groups;
}

}  // namespace

nlohmann::json SegmentsJson(const Segmentation& result, const FrameFileReader& reader,
                            const std::string& archive) {
  nlohmann::json json;
  json["version"] = 1;
  json["archive"] = archive;
  json["mode"] = result.supervised ? "supervised" : "unsupervised";
  json["distance"] = result.distance;
  if (!result.signature.empty()) json["signature"] = result.signature;
  json["window"] = result.window;
  if (result.supervised) {
    json["k"] = result.knn;
    json["neighbours"] = result.one_per_take ? "takes" : "windows";
    json["reference_takes"] = result.reference_takes;
    json["reference_windows"] = result.reference_windows;
  } else {
    json["threshold"] = result.threshold;
    json["group_threshold"] = result.group_threshold;
    json["linkage"] = result.linkage;
  }
  json["labels"] = result.label_names;
  const auto label_of = [&](uint32_t label) {
    return label == kUnlabelled ? nlohmann::json(nullptr)
                                : nlohmann::json(result.label_names[label]);
  };
  nlohmann::json segments = nlohmann::json::array();
  nlohmann::json takes = nlohmann::json::array();
  for (const SegmentedTake& take : result.takes) {
    const ClipInfo& clip = reader.clips()[take.clip];
    for (const LabelledSegment& segment : take.segments) {
      segments.push_back({{"clip", clip.name},
                          {"start", segment.start},
                          {"end", segment.end},
                          {"label", label_of(segment.label)},
                          {"words", segment.end_word - segment.first_word}});
    }
    takes.push_back({{"clip", clip.name},
                     {"frames", clip.frame_count},
                     {"words", take.words},
                     {"segments", take.segments.size()}});
  }
  json["segments"] = segments;
  json["groups"] = GroupsJson(result, reader);
  json["takes"] = takes;
  nlohmann::json skipped = nlohmann::json::array();
  for (uint32_t clip : result.skipped_clips) skipped.push_back(reader.clips()[clip].name);
  json["skipped"] = skipped;
  return json;
}

}  // namespace motif
