// SPDX-License-Identifier: MIT
// The one skeleton every run goes through, whatever its case type (sim/case_type.h): read and check the
// case, open the output folder, print the derived numbers, build the simulation and its observers, read a
// checkpoint when resuming, the run loop (sim/run_loop.h) with its checkpoints, the end's files and
// summary.json (the header, the case type's keys, the division's, the rate), the report, and the hint how
// to resume an interrupted run.
#pragma once
#include "core/config.h"
#include "sim/case_settings.h"
#include "sim/case_type.h"

namespace sabo::sim {

// `sabo run` (and `sabo resume`: req.resume). Exit codes: 0 end time or complete stop, 3 the run failed
// (or an end analysis did), 130 interrupted; bad input throws InputError before anything is written.
int run_case(CaseType& type, const RunRequest& req, const Config& cfg);

// `sabo check`: the keys read and checked, the derived numbers printed; nothing is placed or run.
void check_case(CaseType& type, RunRequest req, const Config& cfg);

}  // namespace sabo::sim
