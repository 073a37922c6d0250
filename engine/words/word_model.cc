#include "engine/words/word_model.h"

#include <string>

#include "engine/signature/ground_distance.h"
#include "engine/signature/word_stream.h"

namespace motif {
namespace {

Result<TensorFile> ReadWordsFile(const std::string& path, const char* kind) {
  Result<TensorFile> file = ReadTensorFile(path, kind);
  if (!file.ok() && file.status().IsNotFound()) {
    return Status::NotFound(path + ": no such file (run `motifmine words` on the archive first)");
  }
  return file;
}

}  // namespace

LoadedWords WordGridOnly(const FrameFileReader& reader, const WordOptions& options) {
  LoadedWords words;
  words.signatures.words = options;
  for (size_t clip = 0; clip < reader.clips().size(); ++clip) {
    words.signatures.clip_words.push_back(ClipWordGrid(reader, clip, options).word_count());
  }
  words.clip_first_words = words.signatures.ClipFirstWords();
  return words;
}

std::vector<uint32_t> LoadedWords::ClipMotifs(size_t clip) const {
  const uint64_t first = clip_first_words[clip];
  return std::vector<uint32_t>(
      signatures.word_motifs.begin() + static_cast<std::ptrdiff_t>(first),
      signatures.word_motifs.begin() +
          static_cast<std::ptrdiff_t>(first + signatures.clip_words[clip]));
}

Result<std::vector<double>> LoadedWords::RangeSignature(size_t clip, uint64_t first,
                                                        uint64_t end) const {
  const uint16_t* motifs = &signatures.word_motifs[clip_first_words[clip]];
  return tf_idf->Signature(std::vector<uint32_t>(motifs + first, motifs + end));
}

std::vector<double> LoadedWords::ClipSignature(size_t clip, bool plain) const {
  if (plain) {
    Result<std::vector<double>> tf = TfIdf::TermFrequencies(ClipMotifs(clip), motifs.motif_count());
    MOTIF_CHECK(tf.ok());
    return *tf;
  }
  const size_t k = signatures.motif_count;
  return std::vector<double>(
      signatures.signatures.begin() + static_cast<std::ptrdiff_t>(clip * k),
      signatures.signatures.begin() + static_cast<std::ptrdiff_t>((clip + 1) * k));
}

Result<LoadedWords> LoadWords(const FrameFileReader& reader, const WordsPaths& paths,
                              bool with_embedding) {
  LoadedWords loaded;
  const uint64_t archive_identity = reader.summary().identity;
  const std::string rerun = " (run `motifmine words` again)";
  MOTIF_ASSIGN_OR_RETURN(TensorFile signatures_file,
                         ReadWordsFile(paths.signatures, kSignaturesKind));
  Result<SignatureSet> signatures = SignaturesFromTensorFile(signatures_file);
  if (!signatures.ok()) return signatures.status().WithContext(paths.signatures);
  loaded.signatures = std::move(signatures.value());
  if (loaded.signatures.archive_identity != archive_identity ||
      loaded.signatures.clip_words.size() != reader.clips().size()) {
    return Status::InvalidArgument(paths.signatures + " was made from another archive than " +
                                   reader.path() + " or another version of it" + rerun);
  }
  MOTIF_ASSIGN_OR_RETURN(TensorFile motifs_file, ReadWordsFile(paths.motifs, kMotifsKind));
  Result<MotifSet> motifs = MotifsFromTensorFile(motifs_file);
  if (!motifs.ok()) return motifs.status().WithContext(paths.motifs);
  loaded.motifs = std::move(motifs.value());
  if (motifs_file.identity() != loaded.signatures.motifs_identity ||
      loaded.motifs.motif_count() != loaded.signatures.motif_count) {
    return Status::InvalidArgument(paths.signatures + " was not made from " + paths.motifs + rerun);
  }
  if (with_embedding) {
    MOTIF_ASSIGN_OR_RETURN(TensorFile embedding_file,
                           ReadWordsFile(paths.embedding, kEmbeddingKind));
    Result<EmbeddingModel> embedding = EmbeddingFromTensorFile(embedding_file);
    if (!embedding.ok()) return embedding.status().WithContext(paths.embedding);
    if (embedding_file.identity() != loaded.motifs.embedding_identity) {
      return Status::InvalidArgument(paths.motifs + " was not made with the embedding " +
                                     paths.embedding + rerun);
    }
    loaded.embedding = std::move(embedding.value());
  }
  loaded.ground = CentroidGroundDistance(loaded.motifs.centroids);
  loaded.clip_first_words = loaded.signatures.ClipFirstWords();
  MOTIF_ASSIGN_OR_RETURN(TfIdf tf_idf,
                         TfIdf::FromDocumentFrequencies(loaded.signatures.take_count,
                                                        loaded.signatures.document_frequencies));
  loaded.tf_idf = std::move(tf_idf);
  return loaded;
}

}  // namespace motif
