// SPDX-License-Identifier: MIT
// Runs a report script (python/report.py, python/sandpile_report.py) on a finished run's folder: PNG plots
// and report.md (Debian's python3 with numpy and matplotlib). A missing interpreter or a failing script is a
// warning, not a run failure: the numerical outputs are complete without the report.
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace sabo::io {

// The python/ folder: $SABO_PYTHON_DIR if set, else the source tree the binary was built from.
[[nodiscard]] std::filesystem::path python_dir();
// Runs `python3 python_dir()/script args...` ($SABO_PYTHON, else /usr/bin/python3, else PATH's); returns its
// exit status (127 when it cannot start).
int run_python(const std::string& script, const std::vector<std::string>& args);
// Runs python/<script> OUT_DIR (report.py for channel runs).
void run_report_script(const std::filesystem::path& out_dir, const std::string& script = "report.py");

}  // namespace sabo::io
