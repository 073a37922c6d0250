#include "engine/report/html_page.h"

#include <cmath>
#include <cstdio>

namespace motif {
namespace {

constexpr char kStyle[] = R"css(
body{font:14px/1.45 system-ui,-apple-system,"Segoe UI",sans-serif;margin:20px auto;max-width:1400px;padding:0 16px;color:#222}
h1{font-size:22px;margin:0 0 4px}h2{font-size:18px;border-bottom:1px solid #ccc;margin-top:28px}
nav a{margin-right:14px}
table.kv td{padding:2px 16px 2px 0;vertical-align:top}table.kv td:first-child{color:#555;white-space:nowrap}
table.t{border-collapse:collapse}table.t td{padding:1px 14px 1px 0}table.t td:nth-child(2){text-align:right}
.note{color:#666;font-size:12px}
.tlrow{display:flex;align-items:center;margin:3px 0}
.tlrow .n{width:170px;flex:none;overflow:hidden;text-overflow:ellipsis;white-space:nowrap;font-size:12px}
.tlrow .w{flex:1;min-width:0}
.tlrow .n small{color:#777}
.axis{position:relative;height:14px;font-size:10px;color:#555;border-bottom:1px solid #bbb}
.axis span{position:absolute;bottom:0;border-left:1px solid #999;padding-left:2px;white-space:nowrap}
.tl{display:block;height:16px;background:#e6e6e6}
.tl rect{fill:currentColor;stroke:currentColor;stroke-width:1px;vector-effect:non-scaling-stroke;cursor:pointer}
.tl rect:hover{opacity:.6}
.motif{border-top:1px solid #ddd;padding:8px 0 4px;margin-top:10px}
.motif h3{margin:0;font-size:16px}
.sw{display:inline-block;width:12px;height:12px;margin-right:7px;border-radius:2px;vertical-align:-1px;background:currentColor}
.meta{margin:2px 0 8px;color:#444;font-size:13px}
.playbox{margin:4px 0 8px}
.player{border:1px solid #ddd;padding:6px;margin-top:4px}
.pbar{display:flex;flex-wrap:wrap;gap:8px;align-items:center;font-size:12px}
.pbar .scrub{flex:1;min-width:160px}
.pmain{display:block;border:1px solid #eee;cursor:grab;margin:4px 0}
.pcmd{display:block;font-size:11px;user-select:all;margin-bottom:4px}
.psmall{display:flex;flex-wrap:wrap;gap:4px}
.pcell{border:2px solid transparent;cursor:pointer;font-size:10px;text-align:center}
.pcell.on{border-color:#888}
.insts{display:flex;flex-wrap:wrap;gap:8px 28px;min-height:186px}
.strip .lbl{font-size:11px;color:#555;white-space:nowrap}
.strip .kf{color:#888;font-size:10px}
.figs{display:flex;min-height:168px}
.fig{flex:none;background:#f6f6f6;margin-right:2px}
.fig path{fill:none;stroke-width:2.2;stroke-linecap:round;stroke-linejoin:round}
button{font:inherit;margin:6px 0}
)css";

}  // namespace

std::string HtmlEscape(const std::string& text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&#39;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

std::string HtmlPageStart(const std::string& title, const std::string& extra_css) {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width,initial-scale=1\">\n"
         "<title>" +
         HtmlEscape(title) + "</title>\n<style>" + kStyle + extra_css + "</style></head><body>\n";
}

std::string HtmlPageEnd() { return "</body></html>\n"; }

std::string HtmlRow(const std::string& key, const std::string& value_html) {
  return "<tr><td>" + key + "</td><td>" + value_html + "</td></tr>\n";
}

std::string HtmlNumber(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

std::string HtmlSeconds(uint64_t frames, double fps) {
  return HtmlNumber("%.2f s", fps > 0 ? static_cast<double>(frames) / fps : 0.0);
}

std::string HtmlBytes(uint64_t bytes) {
  const double value = static_cast<double>(bytes);
  if (value >= 1024.0 * 1024 * 1024) return HtmlNumber("%.2f GiB", value / (1024.0 * 1024 * 1024));
  if (value >= 1024.0 * 1024) return HtmlNumber("%.1f MiB", value / (1024.0 * 1024));
  return HtmlNumber("%.0f KiB", value / 1024.0);
}

std::string HtmlColour(uint32_t id) {
  const int hue = static_cast<int>(std::fmod(id * 137.508, 360.0));
  return "hsl(" + std::to_string(hue) + ",70%," + (id % 2 ? "36%)" : "44%)");
}

}  // namespace motif
