#include "engine/words/word_files.h"

#include <string>

namespace motif {
namespace {

Status CheckKind(const TensorFile& file, const char* kind) {
  if (file.kind() == kind) return Status::Ok();
  return Status::InvalidArgument("a tensor file of kind '" + file.kind() + "', not '" + kind + "'");
}

}  // namespace

std::vector<uint64_t> SignatureSet::ClipFirstWords() const {
  std::vector<uint64_t> first(clip_words.size());
  uint64_t total = 0;
  for (size_t clip = 0; clip < clip_words.size(); ++clip) {
    first[clip] = total;
    total += clip_words[clip];
  }
  return first;
}

TensorFile MotifsToTensorFile(const MotifSet& motifs) {
  TensorFile file(kMotifsKind);
  file.AddF32Matrix("centroids", static_cast<uint64_t>(motifs.centroids.rows()),
                    static_cast<uint64_t>(motifs.centroids.cols()),
                    std::span<const float>(motifs.centroids.data(),
                                           static_cast<size_t>(motifs.centroids.size())));
  file.AddU64("cluster.sizes", motifs.cluster_sizes);
  const double inertia[1] = {motifs.inertia};
  file.AddF64("inertia", inertia);
  const uint64_t identity[4] = {motifs.embedding_identity, motifs.archive_identity, motifs.seed,
                                motifs.iterations};
  file.AddU64("identity", identity);
  return file;
}

Result<MotifSet> MotifsFromTensorFile(const TensorFile& file) {
  MOTIF_RETURN_IF_ERROR(CheckKind(file, kMotifsKind));
  MotifSet motifs;
  MOTIF_ASSIGN_OR_RETURN(auto shape, file.Shape("centroids"));
  if (shape.first == 0 || shape.first > 65535 || shape.second == 0) {
    return Status::Corruption("motifs file: tensor 'centroids' is " + std::to_string(shape.first) +
                              " x " + std::to_string(shape.second) +
                              " (1 to 65535 motifs of at least one dimension)");
  }
  MOTIF_ASSIGN_OR_RETURN(std::vector<float> centroids,
                         file.F32Matrix("centroids", shape.first, shape.second));
  motifs.centroids =
      Eigen::Map<const RowMatrixXf>(centroids.data(), static_cast<Eigen::Index>(shape.first),
                                    static_cast<Eigen::Index>(shape.second));
  MOTIF_ASSIGN_OR_RETURN(motifs.cluster_sizes, file.U64("cluster.sizes", shape.first));
  MOTIF_ASSIGN_OR_RETURN(motifs.inertia, file.ScalarF64("inertia"));
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint64_t> identity, file.U64("identity", 4));
  motifs.embedding_identity = identity[0];
  motifs.archive_identity = identity[1];
  motifs.seed = identity[2];
  motifs.iterations = static_cast<uint32_t>(identity[3]);
  return motifs;
}

TensorFile SignaturesToTensorFile(const SignatureSet& signatures) {
  TensorFile file(kSignaturesKind);
  const uint64_t identity[4] = {signatures.motifs_identity, signatures.archive_identity,
                                signatures.motif_count, signatures.take_count};
  file.AddU64("identity", identity);
  const uint32_t geometry[2] = {signatures.words.word_frames, signatures.words.stride_frames};
  file.AddU32("word.geometry", geometry);
  const double fps[1] = {signatures.words.word_fps};
  file.AddF64("word.fps", fps);
  file.AddU64("clip.words", signatures.clip_words);
  file.AddU16("word.motifs", signatures.word_motifs);
  file.AddU64("document.frequencies", signatures.document_frequencies);
  file.AddF64Matrix("signatures", signatures.clip_words.size(), signatures.motif_count,
                    signatures.signatures);
  return file;
}

Result<SignatureSet> SignaturesFromTensorFile(const TensorFile& file) {
  MOTIF_RETURN_IF_ERROR(CheckKind(file, kSignaturesKind));
  SignatureSet set;
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint64_t> identity, file.U64("identity", 4));
  set.motifs_identity = identity[0];
  set.archive_identity = identity[1];
  if (identity[2] == 0 || identity[2] > 65535) {
    return Status::Corruption("signatures file: motif count " + std::to_string(identity[2]) +
                              " is not in [1, 65535]");
  }
  set.motif_count = static_cast<uint32_t>(identity[2]);
  set.take_count = identity[3];
  MOTIF_ASSIGN_OR_RETURN(std::vector<uint32_t> geometry, file.U32("word.geometry", 2));
  MOTIF_ASSIGN_OR_RETURN(set.words.word_fps, file.ScalarF64("word.fps"));
  set.words.word_frames = geometry[0];
  set.words.stride_frames = geometry[1];
  if (!ValidateWordOptions(set.words).ok()) {
    return Status::Corruption("signatures file: word geometry " + std::to_string(geometry[0]) +
                              " / " + std::to_string(geometry[1]) + " at " +
                              std::to_string(set.words.word_fps) + " Hz is not valid");
  }
  MOTIF_ASSIGN_OR_RETURN(set.clip_words, file.U64("clip.words"));
  MOTIF_ASSIGN_OR_RETURN(set.word_motifs, file.U16("word.motifs"));
  MOTIF_ASSIGN_OR_RETURN(set.document_frequencies,
                         file.U64("document.frequencies", set.motif_count));
  MOTIF_ASSIGN_OR_RETURN(set.signatures,
                         file.F64Matrix("signatures", set.clip_words.size(), set.motif_count));
  uint64_t total = 0;
  uint64_t takes = 0;
  for (uint64_t words : set.clip_words) {
    if (words > set.word_motifs.size() - total) {
      return Status::Corruption("signatures file: the clips' word counts exceed the " +
                                std::to_string(set.word_motifs.size()) + " words");
    }
    total += words;
    takes += words > 0;
  }
  if (total != set.word_motifs.size() || takes != set.take_count) {
    return Status::Corruption("signatures file: " + std::to_string(total) +
                              " words in the clips and " + std::to_string(takes) + " takes, for " +
                              std::to_string(set.word_motifs.size()) +
                              " word motifs and take count " + std::to_string(set.take_count));
  }
  for (size_t word = 0; word < set.word_motifs.size(); ++word) {
    if (set.word_motifs[word] >= set.motif_count) {
      return Status::Corruption("signatures file: word " + std::to_string(word) + " has motif " +
                                std::to_string(set.word_motifs[word]) + " of " +
                                std::to_string(set.motif_count));
    }
  }
  for (uint64_t frequency : set.document_frequencies) {
    if (frequency > set.take_count) {
      return Status::Corruption("signatures file: a document frequency " +
                                std::to_string(frequency) + " above the " +
                                std::to_string(set.take_count) + " takes");
    }
  }
  return set;
}

}  // namespace motif
