#include "engine/evaluation/planted_motif_score.h"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>

#include "common/status.h"

namespace motif {

namespace {

uint64_t Overlap(uint64_t a_start, uint64_t a_end, uint64_t b_start, uint64_t b_end) {
  const uint64_t start = std::max(a_start, b_start);
  const uint64_t end = std::min(a_end, b_end);
  return end > start ? end - start : 0;
}

}  // namespace

bool InstancesHit(uint64_t a_start, uint64_t a_end, uint64_t b_start, uint64_t b_end) {
  const uint64_t shorter = std::min(a_end - a_start, b_end - b_start);
  return shorter > 0 && 2 * Overlap(a_start, a_end, b_start, b_end) >= shorter;
}

PlantedMotifScore ScorePlantedMotifs(const std::vector<FoundInstance>& found,
                                     const std::vector<PlantedInstance>& planted) {
  PlantedMotifScore score;
  score.planted = planted.size();
  score.found = found.size();
  std::set<uint32_t> planted_ids;
  std::set<uint32_t> found_ids;
  for (const PlantedInstance& instance : planted) planted_ids.insert(instance.motif);
  for (const FoundInstance& instance : found) found_ids.insert(instance.motif);
  score.planted_motifs = static_cast<uint32_t>(planted_ids.size());
  score.found_motifs = static_cast<uint32_t>(found_ids.size());

  // Found instances per clip, by start; a planted instance is checked against those that can
  // reach it (found instances of a clip may overlap each other, so scan back by the longest).
  std::unordered_map<std::string, std::vector<size_t>> found_by_clip;
  std::unordered_map<std::string, uint64_t> longest_in_clip;
  for (size_t idx = 0; idx < found.size(); ++idx) {
    found_by_clip[found[idx].clip].push_back(idx);
    uint64_t& longest = longest_in_clip[found[idx].clip];
    longest = std::max(longest, found[idx].end - found[idx].start);
  }
  for (auto& [clip, ids] : found_by_clip) {
    std::sort(ids.begin(), ids.end(), [&](size_t a, size_t b) {
      return std::tie(found[a].start, found[a].end, a) < std::tie(found[b].start, found[b].end, b);
    });
  }
  std::vector<bool> found_hits(found.size(), false);
  std::vector<uint32_t> planted_labels;
  std::vector<uint32_t> found_labels;
  for (const PlantedInstance& target : planted) {
    auto clip = found_by_clip.find(target.clip);
    if (clip == found_by_clip.end()) continue;
    const std::vector<size_t>& ids = clip->second;
    const uint64_t reach = longest_in_clip[target.clip];
    const uint64_t from = target.start > reach ? target.start - reach : 0;
    auto it = std::lower_bound(ids.begin(), ids.end(), from, [&](size_t idx, uint64_t start) {
      return found[idx].start < start;
    });
    bool hit = false;
    // Best: the largest overlap, then the lowest motif id, then the earliest start.
    std::tuple<uint64_t, int64_t, int64_t> best{0, 0, 0};
    uint32_t best_motif = 0;
    for (; it != ids.end() && found[*it].start < target.end; ++it) {
      const FoundInstance& candidate = found[*it];
      if (!InstancesHit(candidate.start, candidate.end, target.start, target.end)) continue;
      found_hits[*it] = true;
      const auto key = std::make_tuple(
          Overlap(candidate.start, candidate.end, target.start, target.end),
          -static_cast<int64_t>(candidate.motif), -static_cast<int64_t>(candidate.start));
      if (!hit || key > best) {
        best = key;
        best_motif = candidate.motif;
      }
      hit = true;
    }
    if (!hit) continue;
    ++score.planted_hit;
    planted_labels.push_back(target.motif);
    found_labels.push_back(best_motif);
  }
  score.found_hitting =
      static_cast<uint64_t>(std::count(found_hits.begin(), found_hits.end(), true));
  score.recall = score.planted
                     ? static_cast<double>(score.planted_hit) / static_cast<double>(score.planted)
                     : 0.0;
  score.precision =
      score.found ? static_cast<double>(score.found_hitting) / static_cast<double>(score.found)
                  : 0.0;
  score.adjusted_rand_index = AdjustedRandIndex(planted_labels, found_labels);
  return score;
}

PlantedMotifScore ScoreMotifsDocument(const MotifsDocument& document,
                                      const std::vector<PlantedInstance>& planted) {
  std::vector<FoundInstance> found;
  for (const MotifsJsonMotif& motif : document.motifs) {
    for (const MotifsJsonInstance& instance : motif.instances) {
      found.push_back({instance.clip, instance.start, instance.end, motif.id});
    }
  }
  return ScorePlantedMotifs(found, planted);
}

}  // namespace motif
