#include "reprs.h"

#include <cstdio>

namespace motifmine_python {
namespace {

// printf's text of `value` in `format` ("%.2f", "%g").
std::string Number(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string Plural(uint64_t count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

}  // namespace

double InstanceSeconds(const motifmine::Instance& instance) {
  return instance.fps > 0 ? static_cast<double>(instance.end - instance.start) / instance.fps : 0;
}

std::string InstanceRepr(const motifmine::Instance& instance) {
  std::string text = "<Instance: " + instance.clip + " frames [" + std::to_string(instance.start) +
                     ", " + std::to_string(instance.end) + ")";
  if (instance.fps > 0) text += ", " + Number("%.2f", InstanceSeconds(instance)) + " s";
  return text + ">";
}

std::string MotifRepr(const motifmine::Motif& motif) {
  std::string text =
      "<Motif " + std::to_string(motif.id) + ": " + Plural(motif.instances.size(), "instance");
  double seconds = 0;
  bool timed = !motif.instances.empty();
  for (const motifmine::Instance& instance : motif.instances) {
    seconds += InstanceSeconds(instance);
    timed = timed && instance.fps > 0;
  }
  if (timed) text += ", mean " + Number("%.2f", seconds / motif.instances.size()) + " s";
  return text + ">";
}

std::string MineResultRepr(const motifmine::MineResult& result) {
  uint64_t instances = 0;
  for (const motifmine::Motif& motif : result.motifs) instances += motif.instances.size();
  uint64_t frames = 0;
  for (const motifmine::Clip& clip : result.clips) frames += clip.frames;
  return "<MineResult: " + Plural(result.motifs.size(), "motif") + ", " +
         Plural(instances, "instance") + ", " + Plural(frames, "frame") + ">";
}

std::string ArchiveRepr(const motifmine::Archive& archive) {
  return "<Archive: " + archive.path() + ", " + Plural(archive.clips().size(), "take") + ", " +
         Plural(archive.frames(), "frame") + " at " + Number("%g", archive.fps()) +
         " fps, skeleton " + archive.skeleton().family + ">";
}

std::string SkeletonRepr(const motifmine::Skeleton& skeleton) {
  std::string text =
      "<Skeleton " + skeleton.family + ": " + Plural(skeleton.joint_names.size(), "joint");
  if (!skeleton.source_joint_names.empty())
    text += ", root '" + skeleton.source_joint_names[0] + "'";
  return text + ">";
}

}  // namespace motifmine_python
