#include "engine/cluster/instances_csv.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <numeric>
#include <unordered_map>

#include "common/file_util.h"

namespace motif {

namespace {

constexpr const char* kHeader =
    "motif,rank,clip,source,start,end,file_first_frame,file_last_frame,start_seconds,"
    "end_seconds,distance\n";

// The shortest decimal that reads back as the same double (as motifs.json writes it).
std::string ExactNumber(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return error == std::errc() ? std::string(buffer, end) : std::string();
}

// Seconds from the source file's frame 0 at clip frame `clip_frame`: the clip starts
// source_first_frame frames of the file's rate in, and runs at the archive's rate.
double FileSeconds(const MotifsJsonClip& clip, uint64_t clip_frame) {
  const double source_fps = clip.source_fps > 0 ? clip.source_fps : clip.fps;
  if (clip.fps <= 0 || source_fps <= 0) return 0;
  return static_cast<double>(clip.source_first_frame) / source_fps +
         static_cast<double>(clip_frame) / clip.fps;
}

std::string Seconds(double seconds) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", seconds);
  return buffer;
}

// One row; `clip` null for an instance of a clip the document does not list (then no file
// frames or seconds).
std::string InstanceRow(uint32_t motif_id, const std::string& rank,
                        const MotifsJsonInstance& instance, const MotifsJsonClip* clip) {
  std::string row = std::to_string(motif_id) + "," + rank + "," + CsvField(instance.clip) + ",";
  row += (clip ? CsvField(clip->source) : "") + ",";
  row += std::to_string(instance.start) + "," + std::to_string(instance.end) + ",";
  if (clip) {
    row += std::to_string(FileFrameOf(*clip, instance.start)) + "," +
           std::to_string(FileFrameOf(*clip, instance.end - 1)) + "," +
           Seconds(FileSeconds(*clip, instance.start)) + "," +
           Seconds(FileSeconds(*clip, instance.end));
  } else {
    row += ",,,";
  }
  row += "," + (instance.distance ? ExactNumber(*instance.distance) : "") + "\n";
  return row;
}

}  // namespace

std::vector<uint32_t> InstanceRanks(const MotifsJsonMotif& motif) {
  if (!motif.representative) return {};
  const size_t count = motif.instances.size();
  std::vector<uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  const uint32_t representative = *motif.representative;
  auto distance = [&](uint32_t inst) { return motif.instances[inst].distance.value_or(0); };
  // Stable: equal distances keep the listed order; the representative first even when another
  // instance is as close (an identical copy).
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    if ((a == representative) != (b == representative)) return a == representative;
    return distance(a) < distance(b);
  });
  std::vector<uint32_t> ranks(count);
  for (uint32_t rank = 0; rank < count; ++rank) ranks[order[rank]] = rank;
  return ranks;
}

std::string CsvField(std::string_view value) {
  if (value.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(value);
  std::string quoted = "\"";
  for (char c : value) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string InstancesCsvText(const MotifsDocument& document) {
  std::unordered_map<std::string, const MotifsJsonClip*> clip_of;
  for (const MotifsJsonClip& clip : document.clips) clip_of[clip.name] = &clip;
  std::string text = kHeader;
  for (const MotifsJsonMotif& motif : document.motifs) {
    const std::vector<uint32_t> ranks = InstanceRanks(motif);
    for (size_t inst = 0; inst < motif.instances.size(); ++inst) {
      const MotifsJsonInstance& instance = motif.instances[inst];
      auto clip = clip_of.find(instance.clip);
      text += InstanceRow(motif.id, ranks.empty() ? "" : std::to_string(ranks[inst]), instance,
                          clip == clip_of.end() ? nullptr : clip->second);
    }
  }
  return text;
}

Status WriteInstancesCsv(const std::string& path, const MotifsDocument& document) {
  Status status = AtomicWriteFile(path, InstancesCsvText(document));
  return status.ok() ? status : status.WithContext("instances file " + path);
}

}  // namespace motif
