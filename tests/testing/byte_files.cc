#include "tests/testing/byte_files.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

namespace motif::testing {

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::error_code error;
  std::filesystem::remove(path, error);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void CopyFile(const std::string& from, const std::string& to) { WriteBytes(to, ReadBytes(from)); }

void PatchByte(const std::string& path, uint64_t offset, char value) {
  std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
  file.seekp(static_cast<std::streamoff>(offset));
  file.put(value);
}

void TruncateFile(const std::string& path, uint64_t size) {
  std::filesystem::resize_file(path, size);
}

bool FileExists(const std::string& path) {
  std::error_code error;
  return std::filesystem::exists(path, error);
}

void ForEachFlippedByte(const std::string& bytes,
                        const std::function<void(const std::string&, const std::string&)>& check) {
  for (size_t byte_idx = 0; byte_idx < bytes.size(); ++byte_idx) {
    for (uint8_t mask : {0x01, 0x10, 0x80}) {
      std::string damaged = bytes;
      damaged[byte_idx] = static_cast<char>(damaged[byte_idx] ^ mask);
      check(damaged, "byte " + std::to_string(byte_idx) + " ^ " + std::to_string(mask));
      if (::testing::Test::HasFailure()) return;
    }
  }
}

}  // namespace motif::testing
