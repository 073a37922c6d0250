#include "formats/frame_file/archive_loader.h"

#include <algorithm>
#include <vector>

#include "formats/format_checks/format_checks.h"

namespace motif::frame_file {
namespace {

// Validates the commit a slot points at: committed length, footer, metadata.
Status LoadCommit(const uint8_t* data, uint64_t size, int slot_idx, const CommitSlot& slot,
                  LoadedArchive* archive) {
  // slot_idx -1: a version named by the caller (LoadArchiveCommit), not by a slot.
  const std::string where =
      (slot_idx < 0 ? std::string("the version") : "commit slot " + std::to_string(slot_idx)) +
      " (generation " + std::to_string(slot.generation) + ")";
  if (slot.committed_length > size) {
    return Status::Corruption("truncated: " + where + " says " +
                              std::to_string(slot.committed_length) +
                              " bytes are committed, the file has " + std::to_string(size));
  }
  if (slot.committed_length < kHeaderBytes + kFooterBytes ||
      slot.footer_offset != slot.committed_length - kFooterBytes) {
    return Status::Corruption(where + ": footer offset " + Hex(slot.footer_offset) +
                              " does not end the committed length " +
                              std::to_string(slot.committed_length));
  }
  Footer footer;
  Status status = Footer::DecodeFrom(data + slot.footer_offset, &footer);
  if (!status.ok()) return status.WithContext("footer at offset " + Hex(slot.footer_offset));
  if (footer.generation != slot.generation) {
    return Status::Corruption("footer at offset " + Hex(slot.footer_offset) + ": generation " +
                              std::to_string(footer.generation) + ", " + where);
  }
  if (!SectionEndsAt(footer.metadata_offset, footer.metadata_bytes, 1, kHeaderBytes,
                     slot.footer_offset)) {
    return Status::Corruption("footer at offset " + Hex(slot.footer_offset) + ": metadata at " +
                              Hex(footer.metadata_offset) + " (" +
                              std::to_string(footer.metadata_bytes) +
                              " bytes) does not end at the footer");
  }
  const uint8_t* metadata_bytes = data + footer.metadata_offset;
  if (Checksum64(metadata_bytes, footer.metadata_bytes) != footer.metadata_checksum) {
    return Status::Corruption("metadata at offset " + Hex(footer.metadata_offset) +
                              ": checksum mismatch");
  }
  ArchiveMetadata metadata;
  MOTIF_RETURN_IF_ERROR(ArchiveMetadata::DecodeFrom(metadata_bytes, footer.metadata_bytes,
                                                    footer.metadata_offset, &metadata));
  archive->active_slot = slot_idx;
  archive->slot = slot;
  archive->footer = footer;
  archive->metadata = std::move(metadata);
  return Status::Ok();
}

// The version whose footer ends the file, named by no valid slot: its slot `slot_idx` is
// damaged. A slot is one 40-byte write after the version's bytes are synced, so a bit flip (or a
// power loss in that write) leaves the newest version whole but unnamed; opening the older one
// in its place, and appending over it, would lose it. OK only for a version newer than
// `newer_than` that validates like any other.
Status LoadFromEndOfFile(const uint8_t* data, uint64_t size, int slot_idx, uint64_t newer_than,
                         LoadedArchive* archive) {
  if (size < kHeaderBytes + kFooterBytes) return Status::Corruption("no version ends the file");
  Footer footer;
  MOTIF_RETURN_IF_ERROR(Footer::DecodeFrom(data + size - kFooterBytes, &footer));
  if (footer.generation <= newer_than) return Status::Corruption("no newer version ends the file");
  CommitSlot slot;
  slot.generation = footer.generation;
  slot.committed_length = size;
  slot.footer_offset = size - kFooterBytes;
  LoadedArchive recovered = *archive;
  MOTIF_RETURN_IF_ERROR(LoadCommit(data, size, slot_idx, slot, &recovered));
  recovered.max_generation = std::max(recovered.max_generation, slot.generation);
  *archive = std::move(recovered);
  return Status::Ok();
}

}  // namespace

Result<LoadedArchive> LoadArchive(const std::string& path, const uint8_t* data, uint64_t size) {
  if (size == 0) return Status::Corruption(path + ": empty file, not a motion archive (.mfs)");
  LoadedArchive archive;
  archive.file_bytes = size;
  Status status = FileHeader::DecodeFixedFrom(data, size, &archive.header);
  if (!status.ok()) return status.WithContext(path);

  struct Candidate {
    int slot_idx;
    CommitSlot slot;
  };
  std::vector<Candidate> candidates;
  std::string slot_errors;
  int damaged_slot = -1;
  for (int slot_idx = 0; slot_idx < 2; ++slot_idx) {
    CommitSlot slot;
    bool is_empty = false;
    Status decoded = CommitSlot::DecodeFrom(data + kSlotOffsets[slot_idx], &slot, &is_empty);
    if (!decoded.ok()) {
      // A torn slot write (an interrupted commit) looks like this: the other slot holds the
      // previous version.
      slot_errors += "; commit slot " + std::to_string(slot_idx) + " at offset " +
                     Hex(kSlotOffsets[slot_idx]) + ": " + decoded.message();
      damaged_slot = slot_idx;
      continue;
    }
    if (is_empty) continue;
    archive.header.slots[slot_idx] = slot;
    candidates.push_back({slot_idx, slot});
    archive.max_generation = std::max(archive.max_generation, slot.generation);
  }
  // The version at the file's end when the slot naming it is damaged (the message for Verify).
  auto recover_newest = [&](uint64_t newer_than) {
    if (damaged_slot < 0 ||
        !LoadFromEndOfFile(data, size, damaged_slot, newer_than, &archive).ok()) {
      return false;
    }
    archive.damaged_slot_reason = path + ": " + slot_errors.substr(2) + "; generation " +
                                  std::to_string(archive.slot.generation) +
                                  " was read from its footer at the end of the file";
    return true;
  };
  if (candidates.empty()) {
    if (recover_newest(0)) return archive;
    return Status::Corruption(path + ": no committed version (both commit slots are empty or " +
                              "damaged" + slot_errors + ")");
  }
  std::stable_sort(
      candidates.begin(), candidates.end(),
      [](const Candidate& a, const Candidate& b) { return a.slot.generation > b.slot.generation; });
  Status newest_error;
  for (const Candidate& candidate : candidates) {
    Status loaded = LoadCommit(data, size, candidate.slot_idx, candidate.slot, &archive);
    if (loaded.ok()) {
      if (archive.slot.committed_length < size && recover_newest(archive.slot.generation)) {
        return archive;
      }
      if (!newest_error.ok()) archive.fallback_reason = path + ": " + newest_error.message();
      return archive;
    }
    if (newest_error.ok()) newest_error = loaded;
  }
  return newest_error.WithContext(path);
}

Result<LoadedArchive> LoadArchiveCommit(const std::string& path, const uint8_t* data, uint64_t size,
                                        uint64_t generation, uint64_t committed_length) {
  if (size == 0) return Status::Corruption(path + ": empty file, not a motion archive (.mfs)");
  LoadedArchive archive;
  archive.file_bytes = size;
  Status status = FileHeader::DecodeFixedFrom(data, size, &archive.header);
  if (!status.ok()) return status.WithContext(path);
  if (generation == 0 || committed_length < kHeaderBytes + kFooterBytes) {
    return Status::Corruption(path + ": no version " + std::to_string(generation) + " of " +
                              std::to_string(committed_length) + " bytes can exist");
  }
  CommitSlot slot;
  slot.generation = generation;
  slot.committed_length = committed_length;
  slot.footer_offset = committed_length - kFooterBytes;
  status = LoadCommit(data, size, /*slot_idx=*/-1, slot, &archive);
  if (!status.ok()) {
    return status.WithContext(path + ": version " + std::to_string(generation) + " (" +
                              std::to_string(committed_length) + " bytes)");
  }
  archive.max_generation = generation;
  return archive;
}

}  // namespace motif::frame_file
