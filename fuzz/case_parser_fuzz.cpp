// SPDX-License-Identifier: MIT
// libFuzzer target: any bytes as a case file (scripts/fuzz.sh). The case is parsed and set up as `sabo
// check` does for its type (every key read and checked, sizes refused arithmetically, nothing run, no
// grains placed). A bad case must end in InputError; anything else escaping (another exception, a crash,
// a sanitizer report, a hang, memory beyond the limit) is a finding.
#include <spdlog/spdlog.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/config.h"
#include "core/error.h"
#include "sim/case_setup.h"
#include "sim/dam_break_run.h"
#include "sim/debris_run.h"
#include "sim/sandpile_run.h"

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
        const std::string type = sim::case_type(cfg);
        if (type == "sandpile") {
            (void)sim::prepare_sandpile(req, cfg);
        } else if (type == "dam_break") {
            (void)sim::prepare_dam_break(req, cfg);
        } else if (type == "debris") {
            (void)sim::prepare_debris(req, cfg);
        } else {
            (void)sim::prepare(req, cfg);
        }
    } catch (const InputError&) {
        // a bad case, said as such
    }
    return 0;
}
