// The script of report.html's player (instance_playback.h has the data it plays): a "play" button
// per motif opens a player of all its instances, time-aligned to the first
// (instance_alignment.h), looping, with play/pause, a scrubber over the selected instance's
// samples, its clip frame, the speed, heading kept or removed, a 3D view turned by dragging, a
// floor, left limbs blue and right limbs red (sides and colours come in the figure's JSON, from
// limb_side.h, as the keyframe strips take them). window.motifPlayers[id] is the player of motif
// id once opened: its state() gives the selected instance's clip, frame, world points and where
// they were drawn (the browser test reads it).
#pragma once

namespace motif {

extern const char kInstancePlayerScript[];

}  // namespace motif
