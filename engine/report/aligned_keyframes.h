// The keyframes of a motif's strips at the same moments of every instance, so that figure k of
// each strip is the same moment of the movement however fast each instance performs it.
//
// The rule: the moments are chosen on the reference instance (the motif's first, the one the
// player aligns to): `keyframes` of its playback samples (instance_playback.h: every step-th
// frame), evenly spaced, the first and the last included. Every instance is aligned to the
// reference by AlignToReference (instance_alignment.h: dynamic time warping of their samples,
// the alignment the player shows); keyframe k of an instance is its sample aligned with the
// reference's keyframe sample k, clip frame start + sample × step. The reference's alignment to
// itself is the identity, so its keyframes are its own evenly spaced samples. An instance at
// half the reference's speed shows, at keyframe k, twice the reference's offset into it.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <vector>

namespace motif {

// The reference's keyframe samples: round(k × (samples − 1) / (keyframes − 1)) for k = 0 ..
// keyframes − 1 (0 for all when keyframes is 1). Precondition: samples >= 1, keyframes >= 1.
std::vector<uint32_t> ReferenceKeySamples(uint32_t reference_samples, uint32_t keyframes);

// The clip frames of an instance's keyframes: start + align[key] × step for each key of
// `key_samples` (ReferenceKeySamples). `align` is AlignToReference of the instance (an entry per
// reference sample); empty: the instance is the reference (the identity).
std::vector<uint64_t> AlignedKeyframeFrames(const std::vector<uint32_t>& key_samples,
                                            const std::vector<uint32_t>& align, uint64_t start,
                                            uint32_t step);

}  // namespace motif
