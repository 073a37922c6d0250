#include "tests/testing/headless_chromium.h"

#include <cstdlib>

#include "common/file_util.h"
#include "tests/testing/run_tool.h"

namespace motif::testing {

std::string FindChromium() {
  if (const char* named = std::getenv("MOTIF_CHROMIUM"); named != nullptr && *named != '\0') {
    return named;
  }
  for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
    RunResult found = RunShell(std::string("command -v ") + name + " 2>/dev/null");
    if (found.exit_code == 0 && !found.output.empty()) {
      return found.output.substr(0, found.output.find('\n'));
    }
  }
  return "";
}

std::string ChromiumCommand(const std::string& chromium, const std::string& profile_dir) {
  return "'" + chromium + "' --headless --no-sandbox --disable-gpu " +
         "--disable-background-networking --disable-component-update --disable-sync " +
         "--no-first-run --hide-scrollbars --user-data-dir='" + profile_dir + "' " +
         "--virtual-time-budget=5000 --enable-logging=stderr --v=0 ";
}

const char kErrorRecorderScript[] =
    "<script>window.__e2eErrors=[];window.addEventListener('error',function(e){"
    "window.__e2eErrors.push(String(e.message)+' (line '+e.lineno+':'+e.colno+')');});"
    "</script>";

InstrumentedRun RunInstrumentedPage(const std::string& chromium, const std::string& page,
                                    const std::string& tail_script,
                                    const std::string& instrumented_path,
                                    const std::string& work_dir) {
  InstrumentedRun run;
  std::string text = page;
  const size_t head = text.find("<head>");
  text.insert(head == std::string::npos ? 0 : head + 6, kErrorRecorderScript);
  const size_t body_end = text.rfind("</body>");
  if (body_end == std::string::npos) {
    run.error = "the page has no </body>";
    return run;
  }
  text.insert(body_end, tail_script);
  if (Status written = AtomicWriteFile(instrumented_path, text); !written.ok()) {
    run.error = written.ToString();
    return run;
  }
  const std::string log_path = work_dir + "/chromium.log";
  const std::string command = ChromiumCommand(chromium, work_dir + "/profile") +
                              "--dump-dom 'file://" + instrumented_path + "' 2>'" + log_path + "'";
  RunResult dom = RunShell("timeout 180 " + command);
  if (auto log = ReadFileToString(log_path); log.ok()) run.log = *log;
  if (dom.exit_code != 0) {
    run.error = "chromium exited " + std::to_string(dom.exit_code) + "\n" + run.log;
    return run;
  }
  const size_t marker = dom.output.find("<pre id=\"e2e-result\"");
  if (marker == std::string::npos) {
    run.error = "the page's load handler did not run\n" + dom.output.substr(0, 2000);
    return run;
  }
  const size_t text_start = dom.output.find('>', marker) + 1;
  const std::string result =
      dom.output.substr(text_start, dom.output.find("</pre>", text_start) - text_start);
  // The DOM text is HTML-escaped; the results hold no & < > except in error messages.
  run.result = nlohmann::json::parse(result, nullptr, false);
  if (!run.result.is_object()) run.error = "not a JSON object: " + result;
  return run;
}

}  // namespace motif::testing
