// Headless Chromium for the tests that check report.html in a real browser: finding the binary,
// its command line, and running a page instrumented with a first script that records uncaught
// errors and a last one that writes a JSON result into a hidden <pre id="e2e-result">, which
// --dump-dom then shows. Tests skip when FindChromium() is empty (Debian: apt-get install
// chromium; scripts/install_deps.sh installs it). $MOTIF_CHROMIUM names another browser binary.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace motif::testing {

// The browser binary, or "" when there is none.
std::string FindChromium();

// The start of a headless command that works as root in a container and touches no network
// (--virtual-time-budget: timers and animation frames run in virtual time, up to 5 s).
std::string ChromiumCommand(const std::string& chromium, const std::string& profile_dir);

// Records uncaught errors in window.__e2eErrors; goes right after <head>.
extern const char kErrorRecorderScript[];

struct InstrumentedRun {
  std::string error;  // non-empty: the run failed, and why (with the browser's log)
  nlohmann::json result;
  std::string log;  // Chromium's stderr (--enable-logging)
};

// Writes `page` with the error recorder after <head> and `tail_script` before </body> to
// `instrumented_path`, loads it in Chromium (profile under `work_dir`) and parses the text of
// <pre id="e2e-result"> as JSON. `tail_script` must create that element.
InstrumentedRun RunInstrumentedPage(const std::string& chromium, const std::string& page,
                                    const std::string& tail_script,
                                    const std::string& instrumented_path,
                                    const std::string& work_dir);

}  // namespace motif::testing
