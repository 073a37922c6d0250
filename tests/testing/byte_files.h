// Whole files as bytes, for the format tests (golden fixtures, corruption, crash recovery).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace motif::testing {

// The file's bytes ("" if it cannot be read).
std::string ReadBytes(const std::string& path);
// Replaces `path` by a new file holding `bytes` (a new file, not a truncated one: ext4 flushes a
// file truncated to zero when it is closed, which makes tests that rewrite files slow).
void WriteBytes(const std::string& path, const std::string& bytes);
void CopyFile(const std::string& from, const std::string& to);
// Overwrites one byte in place (no truncation, for the same reason).
void PatchByte(const std::string& path, uint64_t offset, char value);
void TruncateFile(const std::string& path, uint64_t size);
bool FileExists(const std::string& path);

// Calls check(damaged, what) for `bytes` with each byte in turn flipped by 0x01, 0x10 and 0x80
// ("byte 17 ^ 16"); stops at the first check that leaves the test failed.
void ForEachFlippedByte(const std::string& bytes,
                        const std::function<void(const std::string&, const std::string&)>& check);

}  // namespace motif::testing
