#include "engine/api/public_motifs.h"

#include <map>
#include <string>
#include <utility>

namespace motif {

void CopyMotifsDocument(const MotifsDocument& document, motifmine::MineResult* result) {
  result->clips.clear();
  std::map<std::string, double> clip_fps;
  for (const MotifsJsonClip& clip : document.clips) {
    result->clips.push_back({clip.name, clip.source, clip.first_frame, clip.frames, clip.fps});
    clip_fps[clip.name] = clip.fps;
  }
  result->motifs.clear();
  for (size_t rank = 0; rank < document.motifs.size(); ++rank) {
    motifmine::Motif motif;
    motif.id = static_cast<uint32_t>(rank);
    for (const MotifsJsonInstance& instance : document.motifs[rank].instances) {
      motif.instances.push_back(
          {instance.clip, instance.start, instance.end, clip_fps[instance.clip]});
    }
    result->motifs.push_back(std::move(motif));
  }
}

}  // namespace motif
