#include "tests/testing/golden_hexdump.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "tests/testing/byte_files.h"

namespace motif::testing {

void DumpHexLines(const std::string& bytes, size_t offset, size_t size, const std::string& note,
                  std::ostringstream* out) {
  for (size_t line = 0; line < size; line += 16) {
    char prefix[16];
    std::snprintf(prefix, sizeof(prefix), "%08zx:", offset + line);
    std::string text = prefix;
    for (size_t byte_idx = line; byte_idx < std::min(size, line + 16); ++byte_idx) {
      char hex[4];
      std::snprintf(hex, sizeof(hex), " %02x", static_cast<uint8_t>(bytes[offset + byte_idx]));
      text += hex;
    }
    if (line == 0 && !note.empty()) {
      text.resize(std::max<size_t>(text.size(), 58), ' ');
      text += "| " + note;
    }
    *out << text << "\n";
  }
}

std::string BytesFromSpecHexdump(const std::string& spec_path, std::string* error) {
  const std::string spec = ReadBytes(spec_path);
  const size_t begin = spec.find(kGoldenBegin);
  const size_t end = spec.find(kGoldenEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) {
    *error = spec_path + ": no golden hexdump markers";
    return "";
  }
  std::istringstream lines(
      spec.substr(begin + sizeof(kGoldenBegin), end - begin - sizeof(kGoldenBegin)));
  std::string line, bytes;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#' || line[0] == '`') continue;
    const size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const size_t offset = std::stoul(line.substr(0, colon), nullptr, 16);
    if (offset != bytes.size()) {
      *error = "hexdump line at offset " + line.substr(0, colon) + " does not follow byte " +
               std::to_string(bytes.size());
      return "";
    }
    std::istringstream hex(line.substr(colon + 1, line.find('|') - colon - 1));
    std::string pair;
    while (hex >> pair) bytes.push_back(static_cast<char>(std::stoul(pair, nullptr, 16)));
  }
  return bytes;
}

void ExpectSpecHexdump(const std::string& spec_path, const std::string& dump,
                       const std::string& bytes) {
  const char* update = std::getenv("MOTIF_UPDATE_GOLDEN");
  if (update != nullptr && std::string(update) == "1") std::printf("%s", dump.c_str());
  const std::string spec = ReadBytes(spec_path);
  const size_t begin = spec.find(kGoldenBegin);
  const size_t end = spec.find(kGoldenEnd);
  ASSERT_NE(begin, std::string::npos) << spec_path;
  ASSERT_NE(end, std::string::npos) << spec_path;
  const size_t body = begin + sizeof(kGoldenBegin) - 1 + 1;  // after the marker's newline
  EXPECT_EQ(spec.substr(body, end - body), dump)
      << spec_path << " is out of date; run with MOTIF_UPDATE_GOLDEN=1";
  std::string error;
  EXPECT_EQ(BytesFromSpecHexdump(spec_path, &error), bytes) << error;
}

}  // namespace motif::testing
