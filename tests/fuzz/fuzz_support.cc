#include "tests/fuzz/fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace motif::fuzz {

void Fail(std::string_view what, std::string_view detail) {
  std::fprintf(stderr, "fuzz check failed: %.*s: %.*s\n", static_cast<int>(what.size()),
               what.data(), static_cast<int>(detail.size()), detail.data());
  std::abort();
}

void CheckError(const Status& status, Status::Code expected_code, std::string_view file_name,
                std::string_view where) {
  if (status.ok()) return;
  if (status.code() != expected_code) {
    Fail(where,
         std::string("expected ") + StatusCodeName(expected_code) + ", got " + status.ToString());
  }
  if (status.message().find(file_name) == std::string::npos) {
    Fail(where,
         "the message does not name the file " + std::string(file_name) + ": " + status.ToString());
  }
}

ScratchFile::ScratchFile(std::string_view tag, std::string_view extension) {
  std::error_code error;
  std::filesystem::path dir = std::filesystem::temp_directory_path(error);
  if (error) dir = "/tmp";
  path_ = (dir / ("motif-fuzz-" + std::to_string(::getpid()) + "-" + std::string(tag) +
                  std::string(extension)))
              .string();
}

ScratchFile::~ScratchFile() {
  std::error_code error;
  std::filesystem::remove(path_, error);
}

void ScratchFile::Write(const uint8_t* data, size_t size) {
  std::FILE* file = std::fopen(path_.c_str(), "wb");
  if (file == nullptr) Fail("scratch file", "cannot create " + path_);
  const bool written = size == 0 || std::fwrite(data, 1, size, file) == size;
  if (std::fclose(file) != 0 || !written) Fail("scratch file", "cannot write " + path_);
}

void StoreU64(uint8_t* bytes, uint64_t value) {
  for (int byte_idx = 0; byte_idx < 8; ++byte_idx) {
    bytes[byte_idx] = static_cast<uint8_t>(value >> (8 * byte_idx));
  }
}

}  // namespace motif::fuzz
