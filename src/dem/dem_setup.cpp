// SPDX-License-Identifier: MIT
#include "dem/dem_setup.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/error.h"
#include "dem/friction_calibration.h"

namespace sabo::dem {

namespace {

const char* const class_names[3] = {"particle_particle", "particle_wall", "particle_barrier"};

// Reads contact.<cls>.<key> when the class overrides it, else the shared contact.<key>.
double shared_real(const Config& cfg, const std::string& cls, const std::string& key, double fallback,
                   Range range) {
    const std::string own = "contact." + cls + "." + key;
    if (cfg.has(own)) return cfg.real(own, range);
    return cfg.real_or("contact." + key, fallback, range);
}

double shared_required(const Config& cfg, const std::string& cls, const std::string& key, Range range) {
    const std::string own = "contact." + cls + "." + key;
    return cfg.real(cfg.has(own) ? own : "contact." + key, range);
}

// Sets the normal law's damping (α_n, or β of the Hertz law) so that a head-on impact at `speed`, with the
// attractive force clipped, rebounds with `target` (the achieved restitution; effective_restitution is
// monotone in the damping). Refuses a target below what the most damped underdamped contact reaches.
template <class Normal>
void match_clipped_restitution(Normal& law, double target, double m_eff, double r_eff, double speed,
                               const Config& cfg, const std::string& cls) {
    double& damping = [&]() -> double& {
        if constexpr (std::is_same_v<Normal, LinearNormal>)
            return law.alpha_n;
        else
            return law.beta;
    }();
    const auto achieved = [&](double d) {
        damping = d;
        double tc = 0.0;
        if constexpr (std::is_same_v<Normal, LinearNormal>)
            tc = law.contact_time(m_eff);
        else
            tc = law.contact_time(m_eff, r_eff, speed);
        return effective_restitution(law, m_eff, r_eff, speed, tc);
    };
    double lo = 0.0, hi = 0.99;
    const double least = achieved(hi);
    if (least > target)
        cfg.fail(cfg.has("contact." + cls + ".restitution") ? "contact." + cls + ".restitution"
                                                            : "contact.restitution",
                 fmt::format(
                     "{} cannot be reached with the attractive force clipped (the most damped contact "
                     "rebounds with e = {:.3f}); raise it or set contact.restitution_meaning = \"dashpot\"",
                     target, least));
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (achieved(mid) > target ? lo : hi) = mid;
    }
    damping = 0.5 * (lo + hi);
}

LudingFriction read_friction(const Config& cfg, const std::string& cls, const FrictionPair& fallback,
                             double& mu_r_out, FrictionPair& pp_out) {
    const std::string base = "contact." + cls + ".";
    const bool is_pp = cls == "particle_particle";
    FrictionPair f = fallback;
    if (cfg.has(base + "friction_angle_deg")) {
        if (cfg.has(base + "mu_s") || cfg.has(base + "mu_r")) {
            cfg.fail(base + "friction_angle_deg",
                     "give either friction_angle_deg or mu_s and mu_r, not both");
        }
        const double phi = cfg.real(base + "friction_angle_deg", Range::open_closed(0.0, 60.0));
        const std::string key = base + "friction_angle_deg";
        f = friction_from_repose_angle(phi, key.c_str());
        if (!is_pp) f.mu_r *= 2.0;  // docs/calibration.md: μ_r,pw = 2 μ_r for walls and barrier elements
    } else if (!is_pp && (cfg.has(base + "mu_s_over_pp") || cfg.has(base + "mu_r_over_pp"))) {
        // wall friction as multiples of the particle–particle values (reference case C1: μ_s,pw = 1.5 μ_s,pp)
        if (cfg.has(base + "mu_s") || cfg.has(base + "mu_r")) {
            cfg.fail(base + "mu_s_over_pp", "give either mu_s and mu_r or the ratios *_over_pp, not both");
        }
        f.mu_s = fallback.mu_s * cfg.real_or(base + "mu_s_over_pp", 1.0, Range::non_negative());
        f.mu_r = fallback.mu_r * cfg.real_or(base + "mu_r_over_pp", 2.0, Range::non_negative());
    } else if (cfg.has(base + "mu_s") || cfg.has(base + "mu_r") || is_pp) {
        f.mu_s = cfg.real(base + "mu_s", Range::non_negative());
        f.mu_r = cfg.real(base + "mu_r", Range::non_negative());
    } else {
        f.mu_r *=
            2.0;  // docs/calibration.md default for walls and barrier: μ_s,pw = μ_s,pp, μ_r,pw = 2 μ_r,pp
    }
    if (is_pp) pp_out = f;
    const double ratio = shared_real(cfg, cls, "mu_d_over_mu_s", 0.9, Range::open_closed(0.0, 1.0));
    const double alpha_t = shared_real(cfg, cls, "tangential_damping", 1.0, Range::non_negative());
    const std::string mem_own = base + "friction_memory";
    const std::string memory =
        cfg.has(mem_own) ? cfg.choice(mem_own, {"hysteresis", "none"})
                         : cfg.choice_or("contact.friction_memory", "hysteresis", {"hysteresis", "none"});
    mu_r_out = f.mu_r;
    return {alpha_t, f.mu_s, ratio * f.mu_s,
            memory == "none" ? FrictionMemory::none : FrictionMemory::hysteresis};
}

}  // namespace

DemSolver make_solver(Particles particles, std::vector<Wall> walls, const Vec3& gravity,
                      const DemSettings& settings) {
    DemSolver solver(std::move(particles), std::move(walls), settings.laws, gravity, settings.dt,
                     settings.skin);
    solver.set_skin_max(settings.skin_max);
    solver.set_rolling_sweeps(settings.rolling_sweeps);
    solver.set_reorder_interval(settings.reorder_interval);
    solver.set_overlap_limit(settings.overlap_limit);
    return solver;
}

std::string describe_contact(const DemSettings& d) {
    return fmt::format(
        "contact: {} normal law, restitution zeta = {:.3f} ({}), effective e (attractive force clipped) = "
        "{:.4f}, {} rolling resistance",
        d.normal_model, d.restitution,
        d.restitution_meaning == "achieved" ? "the rebound achieved" : "sets the dashpot",
        d.effective_restitution, d.rolling_model == RollingModel::constraint ? "constraint" : "directional");
}

DemSettings read_dem_settings(const Config& cfg, const GrainScale& g) {
    DemSettings s;
    s.normal_model = cfg.choice_or("contact.normal_model", "linear", {"linear", "hertz"});
    const bool clip = cfg.boolean_or("contact.clip_attractive", true);
    s.restitution_meaning = cfg.choice_or("contact.restitution_meaning", "dashpot", {"dashpot", "achieved"});
    s.rolling_model =
        cfg.choice_or("dem.rolling_model", "constraint", {"constraint", "directional"}) == "constraint"
            ? RollingModel::constraint
            : RollingModel::directional;
    const double m_min = g.density * sphere_volume(g.r_min);
    const double v_impact = 2.0 * g.velocity_scale;

    // keys that only one normal model reads: say so instead of a bare "unknown key"
    const std::vector<std::string> linear_only{"kn_N_m"};
    const std::vector<std::string> hertz_only{"youngs_modulus_Pa", "poisson_ratio", "tangential_stiffness"};
    for (const char* cls : {"", "particle_particle.", "particle_wall.", "particle_barrier."}) {
        const auto& others = s.normal_model == "linear" ? hertz_only : linear_only;
        for (const auto& key : others) {
            const std::string k = std::string("contact.") + cls + key;
            if (cfg.has(k)) {
                cfg.fail(k,
                         fmt::format("is not used by contact.normal_model = \"{}\" (remove it, or choose the "
                                     "model that uses it)",
                                     s.normal_model));
            }
        }
    }

    FrictionPair pp{0.0, 0.0};
    double t_c = 1e300;
    double overlap = 0.0;
    auto build = [&](auto normal_of) {
        using Normal = decltype(normal_of(std::string()));
        ContactLawSet<Normal> set;
        ContactLaw<Normal>* slots[3] = {&set.particle_particle, &set.particle_wall, &set.particle_barrier};
        for (int c = 0; c < 3; ++c) {
            const std::string cls = class_names[c];
            ContactLaw<Normal>& law = *slots[c];
            law.normal = normal_of(cls);
            double mu_r = 0.0;
            law.tangential = read_friction(cfg, cls, pp, mu_r, pp);
            law.rolling.mu_r = mu_r;
            law.rolling.model = s.rolling_model;
            // smallest reduced mass of this class: two smallest grains, or the smallest grain on a wall
            const double m_eff = c == 0 ? 0.5 * m_min : m_min;
            const double r_eff = c == 0 ? 0.5 * g.r_min : g.r_min;
            double tc_c = 0.0;
            if constexpr (std::is_same_v<Normal, LinearNormal>) {
                tc_c = law.normal.contact_time(m_eff);
                overlap =
                    std::max(overlap, g.velocity_scale * std::sqrt(m_eff / law.normal.kn) / (2.0 * g.r_min));
            } else {
                tc_c = law.normal.contact_time(m_eff, r_eff, std::max(v_impact, 1e-3));
                const double v = g.velocity_scale;
                const double d_max =
                    std::pow(15.0 * m_eff * v * v / (16.0 * law.normal.e_star * std::sqrt(r_eff)), 0.4);
                overlap = std::max(overlap, d_max / (2.0 * g.r_min));
            }
            t_c = std::min(t_c, tc_c);
            // calibrated after the contact time: the time step stays that of the dashpot form of ζ. A more
            // damped contact lasts longer but is no softer, and its dashpot wants a shorter step, not a
            // longer one (C2 with t_c/20 of the calibrated law, 1.73e-4 s instead of 1.32e-4: the resting
            // deposit's grains spun up, rotational energy growing, and it never stopped)
            if (s.restitution_meaning == "achieved" && clip)
                match_clipped_restitution(
                    law.normal, shared_required(cfg, cls, "restitution", Range::open_closed(0.0, 1.0)), m_eff,
                    r_eff, std::max(v_impact, 1e-3), cfg, cls);
            if (c == 0) {
                s.restitution = shared_required(cfg, cls, "restitution", Range::open_closed(0.0, 1.0));
                s.effective_restitution =
                    effective_restitution(law.normal, m_eff, r_eff, std::max(v_impact, 1e-3), tc_c);
            }
        }
        s.laws = set;
    };

    if (s.normal_model == "linear") {
        build([&](const std::string& cls) {
            LinearNormal n;
            n.kn = shared_required(cfg, cls, "kn_N_m", Range::positive());
            n.alpha_n = damping_ratio_from_restitution(
                shared_required(cfg, cls, "restitution", Range::open_closed(0.0, 1.0)));
            n.kt_ratio = shared_real(cfg, cls, "kt_over_kn", 2.0 / 7.0, Range::positive());
            n.clip_attractive = clip;
            return n;
        });
    } else {
        build([&](const std::string& cls) {
            HertzNormal n;
            const double e = shared_required(cfg, cls, "youngs_modulus_Pa", Range::positive());
            const double nu = shared_required(cfg, cls, "poisson_ratio", Range::closed(0.0, 0.5));
            // grain–grain: identical grains; grain–wall: rigid wall (infinite modulus)
            const double grains = cls == "particle_particle" ? 2.0 : 1.0;
            n.e_star = e / (grains * (1.0 - nu * nu));
            n.g_star = e / (grains * 2.0 * (2.0 - nu) * (1.0 + nu));
            n.beta = damping_ratio_from_restitution(
                shared_required(cfg, cls, "restitution", Range::open_closed(0.0, 1.0)));
            const std::string rule =
                cfg.choice_or("contact.tangential_stiffness", "mindlin", {"mindlin", "ratio"});
            n.mindlin = rule == "mindlin";
            n.kt_ratio = shared_real(cfg, cls, "kt_over_kn", 2.0 / 7.0, Range::positive());
            n.clip_attractive = clip;
            return n;
        });
    }
    if (g.velocity_scale <= 0.0 && s.normal_model == "hertz") {
        throw InputError(
            fmt::format("{}: the Hertz contact time needs a positive velocity scale "
                        "(set dem.velocity_scale_m_s)",
                        cfg.source()));
    }

    s.contact_time = t_c;
    if (cfg.has("dem.dt_s")) {
        s.dt = cfg.real("dem.dt_s", Range::positive());
        s.steps_per_contact = t_c / s.dt;
        if (s.steps_per_contact < 10.0) {
            cfg.fail("dem.dt_s",
                     fmt::format("dt = {:.4g} s exceeds t_c/10 = {:.4g} s (contact time t_c = {:.4g} s); "
                                 "use at most {:.4g} s or set dem.steps_per_contact >= 10",
                                 s.dt, t_c / 10.0, t_c, t_c / 10.0));
        }
        if (cfg.has("dem.steps_per_contact"))
            cfg.fail("dem.dt_s", "give dem.dt_s or dem.steps_per_contact, not both (each sets the DEM step)");
    } else {
        s.steps_per_contact = static_cast<double>(cfg.integer_or("dem.steps_per_contact", 20, 10, 100000));
        s.dt = t_c / s.steps_per_contact;
    }
    const double skin_over_d = cfg.real_or("dem.skin_over_d", 0.1, Range::open_closed(0.0, 2.0));
    s.skin = skin_over_d * 2.0 * g.r_max;
    const double skin_max_over_d = cfg.real_or(
        "dem.skin_max_over_d", std::max(skin_over_d, default_skin_max_over_d), Range::open_closed(0.0, 2.0));
    if (skin_max_over_d < skin_over_d)
        cfg.fail("dem.skin_max_over_d", fmt::format("the largest skin of a fast grain ({}) must be at least "
                                                    "dem.skin_over_d ({})",
                                                    skin_max_over_d, skin_over_d));
    s.skin_max = skin_max_over_d * 2.0 * g.r_max;
    s.rolling_sweeps = static_cast<int>(cfg.integer_or("dem.rolling_sweeps", 1, 1, 64));
    if (s.rolling_sweeps > 1 && s.rolling_model == RollingModel::directional)
        cfg.fail("dem.rolling_sweeps",
                 "more than one sweep iterates the constraint torque within a step: it applies to "
                 "dem.rolling_model = \"constraint\" (the directional torque is computed once per step)");
    s.reorder_interval = static_cast<int>(cfg.integer_or("dem.reorder_every_builds", 20, 0, 1000000));
    s.expected_max_overlap_ratio = overlap;
    s.overlap_limit = cfg.real_or("dem.max_overlap_over_d", 0.5, Range::open_closed(0.0, 1.0));
    cfg.record("derived.contact_time_s", s.contact_time);
    cfg.record("derived.dt_s", s.dt);
    cfg.record("derived.dt_over_contact_time", s.dt / s.contact_time);
    cfg.record("derived.effective_restitution", s.effective_restitution);
    cfg.record("derived.expected_max_overlap_over_d", s.expected_max_overlap_ratio);
    return s;
}

}  // namespace sabo::dem
