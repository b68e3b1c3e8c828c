// SPDX-License-Identifier: MIT
#include "core/thread_waiting.h"

#include <unistd.h>

#include <cstdlib>
#include <string>

namespace sabo {

void wait_politely(char** argv, long spin_count) {
    if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
    if (::setenv("GOMP_SPINCOUNT", std::to_string(spin_count).c_str(), 1) != 0) return;
    ::execv("/proc/self/exe", argv);
    // (only reached when the re-execution failed: the run goes on as it was started)
    ::unsetenv("GOMP_SPINCOUNT");
}

std::string thread_waiting() {
    std::string out;
    for (const char* key : {"OMP_WAIT_POLICY", "GOMP_SPINCOUNT"})
        if (const char* value = std::getenv(key))
            out += (out.empty() ? "" : " ") + std::string(key) + "=" + value;
    return out.empty() ? "libgomp's default" : out;
}

}  // namespace sabo
