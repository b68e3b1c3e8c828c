// SPDX-License-Identifier: MIT
// libFuzzer target: any bytes as a case file (scripts/fuzz.sh). The case is parsed and set up as `sabo
// check` does for its type (every key read and checked, sizes refused arithmetically, nothing run, no
// grains placed). A bad case must end in InputError; anything else escaping (another exception, a crash,
// a sanitizer report, a hang, memory beyond the limit) is a finding.
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "cases/registry.h"
#include "core/config.h"
#include "core/error.h"
#include "sim/case_settings.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    spdlog::set_level(spdlog::level::off);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace sabo;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const Config cfg = Config::from_string(text, "fuzz.toml");
        sim::RunRequest req{"fuzz.toml", std::filesystem::path("/nonexistent/fuzz_out"), false};
        req.place_grains = false;
        cases::make_case_type(cfg)->prepare(req, cfg);
    } catch (const InputError&) {
        // a bad case, said as such
    }
    return 0;
}
