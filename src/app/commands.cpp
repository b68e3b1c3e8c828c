// SPDX-License-Identifier: MIT
#include "app/commands.h"

#include <spdlog/spdlog.h>

#include "app/case_setup.h"
#include "app/dam_break_run.h"
#include "app/debris_run.h"
#include "app/sandpile_run.h"
#include "core/config.h"

namespace sabo::app {

int check_case(const CaseRequest& req) {
    const Config cfg = Config::from_file(req.case_file, req.overrides);
    if (case_type(cfg) == "sandpile") {
        print_derived(prepare_sandpile(req, cfg));
    } else if (case_type(cfg) == "dam_break") {
        print_derived(prepare_dam_break(req, cfg));
    } else if (case_type(cfg) == "debris") {
        print_derived(prepare_debris(req, cfg));
    } else {
        print_derived(prepare(req, cfg));
    }
    spdlog::info("check passed: {} is valid (nothing was run)", req.case_file.string());
    return 0;
}

}  // namespace sabo::app
