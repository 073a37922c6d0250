#include "engine/report/aligned_keyframes.h"

#include <cmath>

#include "common/status.h"

namespace motif {

std::vector<uint32_t> ReferenceKeySamples(uint32_t reference_samples, uint32_t keyframes) {
  std::vector<uint32_t> samples;
  for (uint32_t key_idx = 0; key_idx < keyframes; ++key_idx) {
    samples.push_back(keyframes == 1 ? 0
                                     : static_cast<uint32_t>(std::llround(
                                           static_cast<double>(key_idx) *
                                           (reference_samples - 1.0) / (keyframes - 1))));
  }
  return samples;
}

std::vector<uint64_t> AlignedKeyframeFrames(const std::vector<uint32_t>& key_samples,
                                            const std::vector<uint32_t>& align, uint64_t start,
                                            uint32_t step) {
  std::vector<uint64_t> frames;
  for (uint32_t key : key_samples) {
    MOTIF_CHECK(align.empty() || key < align.size());
    frames.push_back(start + uint64_t{align.empty() ? key : align[key]} * step);
  }
  return frames;
}

}  // namespace motif
