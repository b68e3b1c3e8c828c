// SPDX-License-Identifier: MIT
#include "core/memory.h"

#include <fstream>
#include <string>

namespace sabo {

double available_memory_bytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    double kb = 0.0;
    std::string unit;
    while (in >> key >> kb >> unit) {
        if (key == "MemAvailable:") return kb * 1024.0;
    }
    return 1e300;
}

}  // namespace sabo
