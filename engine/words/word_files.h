// The motifs (.mwm, kind "motifs") and the signatures (.mws, kind "signatures") of an archive as
// tensor files (docs/formats/tensor_file.md, section 8 lists every tensor):
//  * motifs: the k-means centroids of the archive's embedded words (Aristidou et al. 2018: the
//    motion motifs), their sizes and inertia, and what they were made from (the embedding file's
//    identity, the archive's, the k-means seed);
//  * signatures: every word's motif (the nearest centroid), each clip's word count, the document
//    frequencies of the motifs over the archive's takes, and every take's TF-IDF signature
//    (tf_idf.h), with the identities of the motifs file and the archive.
// Thread-safety: pure functions and value types.
#pragma once

#include <cstdint>
#include <vector>

#include "common/status.h"
#include "engine/signature/k_means.h"
#include "engine/signature/word_grid.h"
#include "formats/tensor_file/tensor_file.h"

namespace motif {

inline constexpr char kMotifsKind[] = "motifs";
inline constexpr char kSignaturesKind[] = "signatures";

struct MotifSet {
  RowMatrixXf centroids;                // k x D
  std::vector<uint64_t> cluster_sizes;  // k
  double inertia = 0;
  uint32_t iterations = 0;
  uint64_t embedding_identity = 0;  // the embedding file's identity (TensorFile::identity)
  uint64_t archive_identity = 0;
  uint64_t seed = 0;
  uint32_t motif_count() const { return static_cast<uint32_t>(centroids.rows()); }
};

struct SignatureSet {
  uint64_t motifs_identity = 0;  // the motifs file's identity
  uint64_t archive_identity = 0;
  uint32_t motif_count = 0;
  WordOptions words;                           // the word geometry the words were cut with
  std::vector<uint64_t> clip_words;            // words of each archive clip
  std::vector<uint16_t> word_motifs;           // the motif of every word, archive word order
  std::vector<uint64_t> document_frequencies;  // takes using each motif
  uint64_t take_count = 0;                     // N of the idf: clips with at least one word
  std::vector<double> signatures;              // clips x motif_count, TF-IDF; 0 rows: no words

  // Word id of clip `clip`'s first word.
  std::vector<uint64_t> ClipFirstWords() const;
};

TensorFile MotifsToTensorFile(const MotifSet& motifs);
// Corruption naming the tensor (missing, wrong type or shape, sizes that disagree);
// InvalidArgument for a file of another kind.
Result<MotifSet> MotifsFromTensorFile(const TensorFile& file);

TensorFile SignaturesToTensorFile(const SignatureSet& signatures);
// As above; also Corruption for a motif id >= motif_count or word counts that do not add up.
Result<SignatureSet> SignaturesFromTensorFile(const TensorFile& file);

}  // namespace motif
