// SPDX-License-Identifier: MIT
// `sabo calibrate`: friction coefficients from an angle of repose (docs/calibration.md), optionally checked
// by a sandpile run, and the calibration sweep over (μ_s, μ_r) that the law is fitted on (reference case C1).
#include <fmt/format.h>
#include <omp.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "app/commands.h"
#include "app/sweep.h"
#include "core/error.h"
#include "dem/friction_calibration.h"

namespace sabo::app {

namespace {

// "first:last:step" or "a,b,c" → values as written for --set (round-off of the steps removed).
std::vector<std::string> value_list(const std::string& text, const char* option) {
    std::vector<double> v;
    try {
        if (text.find(':') != std::string::npos) {
            std::stringstream ss(text);
            std::string a, b, c;
            std::getline(ss, a, ':');
            std::getline(ss, b, ':');
            std::getline(ss, c, ':');
            const double first = std::stod(a), last = std::stod(b), step = std::stod(c);
            if (!(step > 0.0) || last < first) throw std::invalid_argument("range");
            const auto n = static_cast<int>(std::floor((last - first) / step + 1e-9));
            for (int k = 0; k <= n; ++k) v.push_back(first + k * step);
        } else {
            std::stringstream ss(text);
            std::string item;
            while (std::getline(ss, item, ',')) v.push_back(std::stod(item));
        }
    } catch (const std::exception&) {
        throw InputError(
            fmt::format("{} \"{}\": give first:last:step (step > 0, last >= first) or a,b,c", option, text));
    }
    if (v.empty()) throw InputError(fmt::format("{} \"{}\": no values", option, text));
    std::vector<std::string> out;
    for (double x : v) {
        if (x < 0.0)
            throw InputError(fmt::format("{} \"{}\": friction coefficients must be >= 0", option, text));
        out.push_back(fmt::format("{:g}", std::round(x * 1e9) / 1e9));
    }
    return out;
}

// The n-th (0: first) number under `key` in summary.json; NaN when absent or null.
double read_summary_number(const std::filesystem::path& summary, const std::string& key, int nth = 0) {
    std::ifstream in(summary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str(), tag = "\"" + key + "\": ";
    auto at = text.find(tag);
    for (int k = 0; k < nth && at != std::string::npos; ++k) at = text.find(tag, at + 1);
    if (at == std::string::npos || text.compare(at + tag.size(), 4, "null") == 0) return std::nan("");
    return std::stod(text.substr(at + tag.size()));
}

void require_case_file(const std::filesystem::path& file) {
    if (!std::filesystem::exists(file)) {
        throw InputError(fmt::format(
            "--case {}: no such file (the sandpile case; run from the source folder or give --case)",
            file.string()));
    }
}

// Overrides of every calibration sandpile: particle–wall friction tied to particle–particle as the law
// assumes (μ_s,pw = μ_s, μ_r,pw = 2 μ_r: docs/calibration.md, reference case C1's sweep), --particles, then
// the user's --set.
std::vector<std::string> common_overrides(const CalibrateRequest& req) {
    std::vector<std::string> o{"contact.particle_wall.mu_s_over_pp=1",
                               "contact.particle_wall.mu_r_over_pp=2"};
    if (req.particles > 0) o.push_back(fmt::format("sandpile.particles={}", req.particles));
    o.insert(o.end(), req.overrides.begin(), req.overrides.end());
    return o;
}

int calibrate_sweep(const CalibrateRequest& req) {
    require_case_file(req.case_file);
    SweepPlan plan;
    plan.name = "calibration grid";
    plan.case_file = req.case_file;
    plan.out_dir = req.out_dir ? *req.out_dir : std::filesystem::path("out/calibrate/sweep");
    plan.jobs = req.jobs;
    plan.threads = req.threads > 0 ? req.threads : std::max(1, omp_get_max_threads() / req.jobs);
    const std::vector<std::string> common = common_overrides(req);
    add_grid(plan,
             {{"contact.particle_particle.mu_s", value_list(req.mu_s_values, "--mu-s")},
              {"contact.particle_particle.mu_r", value_list(req.mu_r_values, "--mu-r")}},
             common);
    spdlog::info("calibration sweep: {} sandpiles of {}", plan.cases.size(), plan.case_file.string());
    return execute_sweep(plan, "calibration_fit.py");
}

}  // namespace

int run_calibrate(const CalibrateRequest& req) {
    if (req.sweep) {
        if (req.angle_deg || req.mu_s || req.verify)
            throw InputError(
                "--sweep runs the calibration grid; it takes no --angle-deg, --mu-s or --verify");
        return calibrate_sweep(req);
    }
    if (!req.angle_deg) throw InputError("give --angle-deg A (or --sweep)");
    const double phi = *req.angle_deg;
    const dem::FrictionPair pp = req.mu_s ? dem::friction_from_repose_angle(phi, *req.mu_s, "--angle-deg")
                                          : dem::friction_from_repose_angle(phi, "--angle-deg");
    const dem::FrictionPair pw{pp.mu_s, 2.0 * pp.mu_r};
    fmt::print(
        "angle of repose {:g} deg -> friction coefficients (docs/calibration.md: phi = 151.7 sqrt(mu_r "
        "mu_s), "
        "valid for mu_s <= {}, mu_r <= {}; {}):\n"
        "  particle-particle: mu_s = {:.4f}, mu_r = {:.4f}\n"
        "  particle-wall:     mu_s = {:.4f}, mu_r = {:.4f}   (mu_s,pw = mu_s, mu_r,pw = 2 mu_r)\n\n"
        "case-file lines:\n"
        "  [contact.particle_particle]\n  mu_s = {:.4f}\n  mu_r = {:.4f}\n\n"
        "  [contact.particle_wall]\n  mu_s = {:.4f}\n  mu_r = {:.4f}\n",
        phi, dem::calibration_mu_s_max, dem::calibration_mu_r_max,
        req.mu_s ? "mu_s as given" : "mu_s = tan(phi)", pp.mu_s, pp.mu_r, pw.mu_s, pw.mu_r, pp.mu_s, pp.mu_r,
        pw.mu_s, pw.mu_r);
    if (!req.verify) return 0;

    require_case_file(req.case_file);
    CaseRequest run;
    run.case_file = req.case_file;
    run.threads = req.threads;
    run.out_dir =
        req.out_dir ? *req.out_dir : std::filesystem::path(fmt::format("out/calibrate/verify_{:g}", phi));
    run.overwrite = true;  // the verification's folder is this command's: a second verification replaces it
    run.overrides = {fmt::format("contact.particle_particle.mu_s={:.6g}", pp.mu_s),
                     fmt::format("contact.particle_particle.mu_r={:.6g}", pp.mu_r)};
    const auto common = common_overrides(req);
    run.overrides.insert(run.overrides.end(), common.begin(), common.end());
    spdlog::info("verifying with a sandpile: {} -> {}", run.case_file.string(), run.out_dir->string());
    const int rc = run_case(run);
    const auto summary = *run.out_dir / "summary.json";
    const double measured = read_summary_number(summary, "angle_of_repose_deg");
    if (rc != 0 || std::isnan(measured)) {
        spdlog::error("the verification sandpile did not give an angle (exit {}); see {}", rc,
                      (*run.out_dir / "sabo.log").string());
        return rc != 0 ? rc : 3;
    }
    fmt::print(
        "verification: target {:.2f} deg, measured {:.2f} deg (left {:.2f}, right {:.2f}), difference "
        "{:+.2f} deg — {}\n",
        phi, measured, read_summary_number(summary, "angle_deg", 0),
        read_summary_number(summary, "angle_deg", 1), measured - phi, (*run.out_dir / "report.md").string());
    return 0;
}

}  // namespace sabo::app
