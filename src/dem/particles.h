// SPDX-License-Identifier: MIT
// Particle storage: structure of arrays, one array per property. Mobile spheres occupy
// [0, n_mobile); fixed spheres (barrier elements of the "overlapping spheres" model) follow them,
// have zero inverse mass and inertia and never move. See docs/dem.md for the layout.
#pragma once
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/vec3.h"

namespace sabo::dem {

// Volume of a sphere of radius r, m³.
[[nodiscard]] inline double sphere_volume(double r) {
    return 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

struct KineticEnergy {
    double translational = 0.0;  // J
    double rotational = 0.0;     // J
};

struct Particles {
    std::vector<Vec3> x;        // position, m
    std::vector<Vec3> v;        // velocity, m/s
    std::vector<Vec3> w;        // angular velocity, rad/s
    std::vector<Vec3> f;        // contact (+ fluid) force of the last evaluation, N (gravity not included)
    std::vector<Vec3> t;        // torque, N·m
    std::vector<double> r;      // radius, m
    std::vector<double> m;      // mass, kg (0 for fixed)
    std::vector<double> inv_m;  // 1/m (0 for fixed)
    std::vector<double> inv_j;  // 1/J, J = 2/5 m r² (0 for fixed)
    std::size_t n_mobile = 0;

    [[nodiscard]] std::size_t size() const { return x.size(); }
    [[nodiscard]] std::size_t n_fixed() const { return x.size() - n_mobile; }
    // ½ m v² + ½ J ω² of mobile grain i, J (from v and w: synchronous ones for a solver's state).
    [[nodiscard]] double kinetic_energy(std::size_t i) const {
        return 0.5 * m[i] * norm2(v[i]) + 0.5 / inv_j[i] * norm2(w[i]);
    }
    // The mobile grains' kinetic energy, J (from v and w), each part summed in index order.
    [[nodiscard]] KineticEnergy kinetic_energies() const {
        KineticEnergy e;
        for (std::size_t i = 0; i < n_mobile; ++i) {
            e.translational += 0.5 * m[i] * norm2(v[i]);
            e.rotational += 0.5 / inv_j[i] * norm2(w[i]);
        }
        return e;
    }

    // Adds a mobile sphere; must be called before any add_fixed().
    void add_mobile(const Vec3& pos, double radius, double density, const Vec3& vel = {}) {
        const double mass = density * sphere_volume(radius);
        push(pos, radius, mass, 1.0 / mass, 1.0 / (0.4 * mass * radius * radius), vel);
        ++n_mobile;
    }
    void add_fixed(const Vec3& pos, double radius) { push(pos, radius, 0.0, 0.0, 0.0, {}); }

    // Checkpoints (io/checkpoint.h): every array and the mobile count.
    template <class Archive>
    void transfer(Archive& a) {
        a(x, v, w, f, t, r, m, inv_m, inv_j, n_mobile);
    }

  private:
    void push(const Vec3& pos, double radius, double mass, double im, double ij, const Vec3& vel) {
        x.push_back(pos);
        v.push_back(vel);
        w.push_back({});
        f.push_back({});
        t.push_back({});
        r.push_back(radius);
        m.push_back(mass);
        inv_m.push_back(im);
        inv_j.push_back(ij);
    }
};

}  // namespace sabo::dem
