// SPDX-License-Identifier: MIT
#include "core/memory.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>

#include "core/mpi_world.h"

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

double memory_of_all_machines_bytes() {
    int local = 0;
    for (const char* name : {"OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"})
        if (const char* v = std::getenv(name); v != nullptr && local <= 0) local = std::atoi(v);
    const int ranks = MpiWorld::launcher_size();
    const int machines = local > 0 ? std::max(1, ranks / local) : 1;
    return available_memory_bytes() * machines;
}

}  // namespace sabo
