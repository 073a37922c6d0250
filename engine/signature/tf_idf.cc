#include "engine/signature/tf_idf.h"

#include <cmath>
#include <string>
#include <utility>

namespace motif {

double TfIdf::InverseDocumentFrequency(uint64_t take_count, uint64_t document_frequency) {
  return std::log((1.0 + static_cast<double>(take_count)) /
                  (1.0 + static_cast<double>(document_frequency))) +
         1.0;
}

TfIdf::TfIdf(uint64_t take_count, std::vector<uint64_t> document_frequencies)
    : take_count_(take_count), document_frequencies_(std::move(document_frequencies)) {
  idf_.reserve(document_frequencies_.size());
  for (uint64_t frequency : document_frequencies_) {
    idf_.push_back(InverseDocumentFrequency(take_count_, frequency));
  }
}

Result<TfIdf> TfIdf::Fit(std::span<const std::vector<uint32_t>> takes, uint32_t motif_count) {
  if (motif_count == 0) return Status::InvalidArgument("TF-IDF: no motifs");
  if (takes.empty()) return Status::InvalidArgument("TF-IDF: no takes");
  std::vector<uint64_t> frequencies(motif_count, 0);
  // last_take[m] = 1 + the last take that counted motif m, so each take counts a motif once.
  std::vector<uint64_t> last_take(motif_count, 0);
  for (size_t take_idx = 0; take_idx < takes.size(); ++take_idx) {
    const std::vector<uint32_t>& words = takes[take_idx];
    for (size_t word_idx = 0; word_idx < words.size(); ++word_idx) {
      const uint32_t motif = words[word_idx];
      if (motif >= motif_count) {
        return Status::InvalidArgument(
            "TF-IDF: take " + std::to_string(take_idx) + ", word " + std::to_string(word_idx) +
            ": motif " + std::to_string(motif) + " >= " + std::to_string(motif_count) + " motifs");
      }
      if (last_take[motif] != take_idx + 1) {
        last_take[motif] = take_idx + 1;
        ++frequencies[motif];
      }
    }
  }
  return TfIdf(takes.size(), std::move(frequencies));
}

Result<TfIdf> TfIdf::FromDocumentFrequencies(uint64_t take_count,
                                             std::vector<uint64_t> document_frequencies) {
  if (document_frequencies.empty()) return Status::InvalidArgument("TF-IDF: no motifs");
  if (take_count == 0) return Status::InvalidArgument("TF-IDF: no takes");
  for (size_t motif = 0; motif < document_frequencies.size(); ++motif) {
    if (document_frequencies[motif] > take_count) {
      return Status::InvalidArgument("TF-IDF: motif " + std::to_string(motif) + " is used by " +
                                     std::to_string(document_frequencies[motif]) + " takes of " +
                                     std::to_string(take_count));
    }
  }
  return TfIdf(take_count, std::move(document_frequencies));
}

Result<std::vector<double>> TfIdf::TermFrequencies(std::span<const uint32_t> words,
                                                   uint32_t motif_count) {
  if (words.empty()) return Status::InvalidArgument("TF-IDF: a signature needs at least one word");
  std::vector<uint64_t> counts(motif_count, 0);
  for (size_t word_idx = 0; word_idx < words.size(); ++word_idx) {
    if (words[word_idx] >= motif_count) {
      return Status::InvalidArgument("TF-IDF: word " + std::to_string(word_idx) + ": motif " +
                                     std::to_string(words[word_idx]) +
                                     " >= " + std::to_string(motif_count) + " motifs");
    }
    ++counts[words[word_idx]];
  }
  std::vector<double> frequencies(motif_count, 0.0);
  const double word_count = static_cast<double>(words.size());
  for (uint32_t motif = 0; motif < motif_count; ++motif) {
    frequencies[motif] = static_cast<double>(counts[motif]) / word_count;
  }
  return frequencies;
}

Result<std::vector<double>> TfIdf::Signature(std::span<const uint32_t> words) const {
  MOTIF_ASSIGN_OR_RETURN(std::vector<double> signature, TermFrequencies(words, motif_count()));
  for (uint32_t motif = 0; motif < motif_count(); ++motif) signature[motif] *= idf_[motif];
  return signature;
}

}  // namespace motif
