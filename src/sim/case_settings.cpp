// SPDX-License-Identifier: MIT
#include "sim/case_settings.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "dem/grain_budget.h"

namespace sabo::sim {

void check_memory(const Config& cfg, std::size_t spheres) {
    const dem::MemoryNeed m = dem::memory_need(static_cast<double>(spheres));
    if (!m.fits()) {
        throw InputError(
            fmt::format("{}: the run needs about {:.1f} GiB but only {:.1f} GiB of memory is available",
                        cfg.source(), m.need_bytes / 1073741824.0, m.available_bytes / 1073741824.0));
    }
}

OutputSettings read_output_settings(const Config& cfg, const RunRequest& req, const std::string& case_name,
                                    double frame_default, double series_default) {
    // the default folder is out/<name>: a name that is a path would put the run elsewhere (out/../../x)
    if (case_name.empty() || case_name == "." || case_name == ".." ||
        case_name.find_first_of("/\\") != std::string::npos)
        cfg.fail("case.name", fmt::format("'{}' is a path: a case's name is a name (the run's folder is "
                                          "out/<name>; --out or output.dir choose another)",
                                          case_name));
    OutputSettings out;
    out.frame_interval = cfg.real_or("output.frame_interval_s", frame_default, Range::positive());
    out.series_interval = cfg.real_or("output.series_interval_s", series_default, Range::positive());
    out.progress_interval = cfg.real_or("output.progress_interval_wall_s", 5.0, Range::positive());
    out.report = cfg.boolean_or("output.report", true);
    out.checkpoint_wall_s = cfg.real_or("output.checkpoint_interval_wall_s", 600.0, Range::non_negative());
    out.checkpoint_sim_s = cfg.real_or("output.checkpoint_interval_s", 0.0, Range::non_negative());
    out.out_dir =
        req.out_dir ? *req.out_dir : std::filesystem::path(cfg.text_or("output.dir", "out/" + case_name));
    return out;
}

}  // namespace sabo::sim
