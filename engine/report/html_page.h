// What every HTML page of motifmine shares (the motif report, and the search and classify pages):
// one self-contained file with inline CSS, no network access. The page style, escaping, number
// formatting and the motif colours live here so the pages look alike.
// Thread-safety: pure functions.
#pragma once

#include <cstdint>
#include <string>

#include "common/count_text.h"  // WithCommas, CountOf, which the pages use

namespace motif {

// `text` with & < > " ' replaced by character references, safe in HTML text and attributes.
std::string HtmlEscape(const std::string& text);

// "<!DOCTYPE html>...<title>TITLE</title><style>" + the shared style + `extra_css` +
// "</style></head><body>\n".
std::string HtmlPageStart(const std::string& title, const std::string& extra_css = "");
// "</body></html>\n"
std::string HtmlPageEnd();

// "<tr><td>KEY</td><td>VALUE</td></tr>\n": a row of a key-value table (neither is escaped).
std::string HtmlRow(const std::string& key, const std::string& value_html);

// printf of one double ("%.2f").
std::string HtmlNumber(const char* format, double value);
// "2.50 s" for a frame count at `fps`.
std::string HtmlSeconds(uint64_t frames, double fps);

// "512 KiB", "1.5 MiB", "2.00 GiB".
std::string HtmlBytes(uint64_t bytes);
// A fixed colour per id (motif, group, label): hues a golden angle apart, so neighbouring ids
// never look alike. "hsl(h,70%,l%)".
std::string HtmlColour(uint32_t id);

}  // namespace motif
