// LoadedWords: what `motifmine words` wrote for an archive, read back and checked to belong to it
// and to each other, for search and classify: the embedding (to embed query words), the motifs
// with their ground distance, and the signatures with every word's motif and the archive's idf.
// Thread-safety: a value type; const methods are safe from many threads.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "common/status.h"
#include "engine/embedding/embedding_file.h"
#include "engine/signature/tf_idf.h"
#include "engine/words/word_files.h"
#include "engine/words/words_builder.h"
#include "formats/frame_file/frame_file_reader.h"

namespace motif {

struct LoadedWords {
  std::optional<EmbeddingModel> embedding;  // only if asked for
  MotifSet motifs;
  SignatureSet signatures;
  Eigen::MatrixXd ground;                  // k x k centroid distances
  std::vector<uint64_t> clip_first_words;  // word id of each clip's first word
  std::optional<TfIdf> tf_idf;

  // The motifs of clip `clip`'s words.
  std::vector<uint32_t> ClipMotifs(size_t clip) const;
  // The TF-IDF signature of words [first, end) of clip `clip` (first < end <= its words).
  Result<std::vector<double>> RangeSignature(size_t clip, uint64_t first, uint64_t end) const;
  // The signature of clip `clip` (its row), TF-IDF or, with `plain`, term frequencies only.
  std::vector<double> ClipSignature(size_t clip, bool plain) const;
};

// Where the words of `reader`'s archive lie when cut with `options`, and nothing else: no
// embedding, motifs or signatures (signatures.clip_words, signatures.words and clip_first_words
// are filled; there is no idf). For what needs only the words' places: `segment`'s word
// signatures and its DTW baseline, when no words files were built.
LoadedWords WordGridOnly(const FrameFileReader& reader, const WordOptions& options);

// Reads the files of `paths` and checks them against `reader`'s archive. NotFound (with a hint to
// run `motifmine words`) for a missing file; InvalidArgument when the files were made from
// another archive or from each other's older versions; Corruption from the files.
Result<LoadedWords> LoadWords(const FrameFileReader& reader, const WordsPaths& paths,
                              bool with_embedding);

}  // namespace motif
