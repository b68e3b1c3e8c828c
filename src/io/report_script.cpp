// SPDX-License-Identifier: MIT
#include "io/report_script.h"

#include <spawn.h>
#include <spdlog/spdlog.h>
#include <sys/wait.h>

#include <cstdlib>

extern char** environ;

namespace sabo::io {

std::filesystem::path python_dir() {
    if (const char* env = std::getenv("SABO_PYTHON_DIR"); env != nullptr && *env != '\0') return env;
    return SABO_SOURCE_PYTHON_DIR;
}

// $SABO_PYTHON, else Debian's /usr/bin/python3 (where apt installs numpy and matplotlib, even when
// another python3 comes first on PATH), else python3 from PATH.
std::string python_interpreter() {
    if (const char* env = std::getenv("SABO_PYTHON"); env != nullptr && *env != '\0') return env;
    if (std::filesystem::exists("/usr/bin/python3")) return "/usr/bin/python3";
    return "python3";
}

int run_python(const std::string& script, const std::vector<std::string>& args) {
    const std::string python = python_interpreter();
    std::vector<std::string> argv_s{python, (python_dir() / script).string()};
    argv_s.insert(argv_s.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_s) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    if (posix_spawnp(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ) != 0) return 127;
    int status = 0;
    if (waitpid(pid, &status, 0) < 0) return 127;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

void run_report_script(const std::filesystem::path& out_dir, const std::string& script) {
    const int rc = run_python(script, {out_dir.string()});
    if (rc == 0) {
        spdlog::info("report: {}", (out_dir / "report.md").string());
    } else {
        spdlog::warn(
            "the report script python/{} failed (exit {}): plots and report.md are missing; "
            "needs python3, python3-numpy, python3-matplotlib (set SABO_PYTHON_DIR if the sources moved)",
            script, rc);
    }
}

}  // namespace sabo::io
