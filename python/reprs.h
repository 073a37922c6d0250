// The repr() of the module's objects (docs/python.md): one line saying what the object holds,
// <Type: ...>, as a reader at the interpreter wants to see it.
#pragma once

#include <string>

#include <motifmine/motifmine.h>

namespace motifmine_python {

// <Instance: synth_000000 frames [343, 1055), 5.93 s>
std::string InstanceRepr(const motifmine::Instance& instance);
// <Motif 0: 5 instances, mean 5.65 s>
std::string MotifRepr(const motifmine::Motif& motif);
// <MineResult: 3 motifs, 15 instances, 20000 frames>
std::string MineResultRepr(const motifmine::MineResult& result);
// <Archive: a.mfs, 5 takes, 20000 frames at 120 fps, skeleton cmu31>
std::string ArchiveRepr(const motifmine::Archive& archive);
// <Skeleton cmu31: 31 joints, root 'Hips'> (the root's source name)
std::string SkeletonRepr(const motifmine::Skeleton& skeleton);

// An instance's length in seconds at its clip's rate; 0 when the rate is unknown.
double InstanceSeconds(const motifmine::Instance& instance);

}  // namespace motifmine_python
