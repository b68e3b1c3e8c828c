// SPDX-License-Identifier: MIT
#include "dem/dem_solver.h"

#include <fmt/format.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/stopwatch.h"
#include "dem/contact_batch.h"
#include "dem/mesh_contacts.h"
#include "dem/spatial_order.h"

namespace sabo::dem {

DemSolver::DemSolver(Particles particles, std::vector<Wall> walls, AnyContactLaws laws, const Vec3& gravity,
                     double dt, double skin)
    : p_(std::move(particles)),
      walls_(std::move(walls)),
      laws_(std::move(laws)),
      gravity_(gravity),
      dt_(dt),
      skin_(skin),
      skin_max_(skin),
      wall_force_(walls_.size()) {
    if (walls_.size() > 65535) throw InputError("more than 65535 walls");
    ids_.resize(p_.size());
    for (std::size_t i = 0; i < ids_.size(); ++i) ids_[i] = static_cast<std::uint32_t>(i);
    for (std::size_t i = 0; i < p_.n_mobile; ++i) r_max_ = std::max(r_max_, p_.r[i]);
    refresh();
}

void DemSolver::refresh() {
    lists_stale_ = true;
    const std::size_t n = p_.size();
    contact_count_.resize(n);
    rolling_dm_.resize(n);
    parked_.assign(n, 1);
    recv_.assign(n, Received{});
    synchronize();  // the caller edited the synchronous state
    step_gravity_ = gravity_;
    vh_ = p_.v;  // this evaluation's contact kinematics use the given velocities
    wh_ = p_.w;
    compute_forces();
    // leapfrog state after a force evaluation: v half a step behind (the drift kicks it by Δt before
    // moving), ω half a step ahead (the rolling sweep of the next step acts on it)
    const double h = 0.5 * dt_;
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        vh_[i] = p_.v[i] - h * (p_.f[i] * p_.inv_m[i] + gravity_);
        wh_[i] = p_.w[i] + h * p_.inv_j[i] * p_.t[i];
    }
}

void DemSolver::set_rolling_sweeps(int sweeps) {
    if (sweeps < 1) throw InputError("rolling sweeps must be at least 1");
    rolling_sweeps_ = sweeps;
}

void DemSolver::set_skin_max(double skin_max) {
    if (!(skin_max >= skin_)) throw InputError("the largest skin must be at least the skin");
    skin_max_ = skin_max;
    lists_stale_ = true;
}

void DemSolver::set_reorder_interval(int builds) {
    if (builds < 0) throw InputError("the reorder interval must be >= 0 list builds");
    reorder_interval_ = builds;
    // the first sort at the next build: the order the grains were generated in is arbitrary (a release
    // lattice numbered layer by layer cuts the threads' ranges along the flow)
    builds_since_reorder_ = builds > 0 ? builds - 1 : 0;
}

namespace {
// v[k] = old v[order[k]] for k < order.size(); the entries from n_mobile on (fixed spheres) move down
// to follow (order may leave grains out) and keep their order
template <class T>
void permute(std::vector<T>& v, const std::vector<std::uint32_t>& order, std::size_t n_mobile) {
    std::vector<T> old(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n_mobile));
    for (std::size_t k = 0; k < order.size(); ++k) v[k] = old[order[k]];
    v.erase(v.begin() + static_cast<std::ptrdiff_t>(order.size()),
            v.begin() + static_cast<std::ptrdiff_t>(n_mobile));
}
}  // namespace

void DemSolver::remove_mobile(const std::vector<std::uint8_t>& gone) {
    if (gone.size() != p_.n_mobile)
        throw InputError(
            fmt::format("remove_mobile: {} flags for {} mobile grains", gone.size(), p_.n_mobile));
    if (std::none_of(gone.begin(), gone.end(), [](std::uint8_t g) { return g != 0; })) return;
    if (gone_.empty()) gone_.assign(p_.n_mobile, 0);
    for (std::size_t i = 0; i < gone.size(); ++i) gone_[i] |= gone[i];
    lists_stale_ = true;
}

// Sorts the mobile grains by cell and/or drops the removed ones; rebuild_lists() then remaps the
// contact histories through order_. Runs every reorder_interval_ builds or after a removal, so its
// allocations are rare.
void DemSolver::renumber_grains(bool sort) {
    const std::size_t nm = p_.n_mobile;
    if (sort) {
        spatial_order(p_.x, nm, 2.0 * r_max_ + skin_, order_, order_start_, order_histogram_);
    } else {
        order_.resize(nm);
        for (std::size_t i = 0; i < nm; ++i) order_[i] = static_cast<std::uint32_t>(i);
    }
    if (!gone_.empty()) {  // removed_now_ was reset by rebuild_lists()
        std::erase_if(order_, [&](std::uint32_t i) { return gone_[i] != 0; });
        removed_now_ = nm - order_.size();
        removed_total_ += removed_now_;
        gone_.clear();
    }
    permute(p_.x, order_, nm);
    permute(p_.v, order_, nm);
    permute(p_.w, order_, nm);
    permute(p_.f, order_, nm);
    permute(p_.t, order_, nm);
    permute(p_.r, order_, nm);
    permute(p_.m, order_, nm);
    permute(p_.inv_m, order_, nm);
    permute(p_.inv_j, order_, nm);
    permute(vh_, order_, nm);
    permute(wh_, order_, nm);
    if (external_) {
        permute(external_force_, order_, nm);
        permute(external_torque_, order_, nm);
    }
    permute(contact_count_, order_, nm);
    permute(ids_, order_, nm);
    p_.n_mobile = order_.size();
    if (removed_now_ > 0) {  // per-grain scratch: contents are rewritten before use, only the size counts
        const std::size_t n = p_.size();
        rolling_dm_.resize(n);
        parked_.resize(n);
        recv_.resize(n);
    }
}

void DemSolver::set_external_forces(std::span<const Vec3> force, std::span<const Vec3> torque) {
    const std::size_t nm = p_.n_mobile;
    if (force.size() != nm || torque.size() != nm)
        throw InputError(fmt::format("set_external_forces: {} forces and {} torques for {} mobile grains",
                                     force.size(), torque.size(), nm));
    if (!external_) {
        external_ = true;
        external_force_.assign(nm, Vec3{});
        external_torque_.assign(nm, Vec3{});
    }
    const double h = 0.5 * dt_;
    for (std::size_t i = 0; i < nm; ++i) {
        // A force that jumps at t kicks by ½Δt (F⁻ + F⁺) across t (velocity Verlet on either side), so v(t)
        // is continuous and a force held over [t, t + nΔt] gives exactly the impulse F nΔt. The current
        // state's force changes by the difference; v is kicked in the next drift by Δt F⁺, so its half-step
        // value loses ½Δt ΔF/m; ω was already kicked with Δt T⁻ (finish_forces_of) and gains ½Δt ΔT/J.
        const Vec3 df = force[i] - external_force_[i], dm = torque[i] - external_torque_[i];
        p_.f[i] += df;
        p_.t[i] += dm;
        vh_[i] -= h * (p_.inv_m[i] * df);
        wh_[i] += h * (p_.inv_j[i] * dm);
        external_force_[i] = force[i];
        external_torque_[i] = torque[i];
    }
    synced_ = false;
}

void DemSolver::pack_grains(std::span<const std::uint32_t> indices, std::vector<GrainRecord>& out) const {
    for (const std::uint32_t i : indices) {
        out.push_back({p_.x[i], vh_[i], wh_[i], p_.f[i], p_.t[i], external_ ? external_force_[i] : Vec3{},
                       external_ ? external_torque_[i] : Vec3{}, p_.r[i], p_.m[i], p_.inv_m[i], p_.inv_j[i],
                       ids_[i], contact_count_[i]});
    }
}

void DemSolver::add_mobile(std::vector<GrainRecord> arriving) {
    if (ghost_count_ != 0) throw InputError("add_mobile: the grains are divided among processes");
    if (arriving.empty()) return;
    if (next_id_ == 0)
        for (const std::uint32_t id : ids_) next_id_ = std::max(next_id_, id + 1);
    for (GrainRecord& g : arriving) {
        if (next_id_ >= first_wall_key) throw RunError("add_mobile: the run has used every grain id");
        g.id = next_id_++;
    }
    if (!gone_.empty() || lists_stale_ || list_.builds() == 0) rebuild_lists_now();  // removals pending
    std::vector<ContactRecord> contacts;
    contact_records(contacts);
    std::vector<std::uint32_t> present(p_.n_mobile);
    for (std::size_t i = 0; i < present.size(); ++i) present[i] = static_cast<std::uint32_t>(i);
    std::vector<GrainRecord> grains;
    grains.reserve(present.size() + arriving.size());
    pack_grains(present, grains);
    grains.insert(grains.end(), arriving.begin(), arriving.end());
    replace_mobile(grains, 0, std::move(contacts));
    rebuild_lists_now();
}

void DemSolver::contact_records(std::vector<ContactRecord>& out) const {
    const std::size_t rows = own_count();
    for (std::size_t i = 0; i < rows; ++i) {
        for (auto k = list_.begin(i); k < list_.end(i); ++k) {
            if (pair_touch_[k] == 0) continue;
            const std::uint32_t a = ids_[i], b = ids_[list_.partner(k)];
            const ContactRecord seen_from_a{a, b, pair_hist_[k], pair_roll_[k], pair_fn_[k]};
            out.push_back(a < b ? seen_from_a : mirrored(seen_from_a));
        }
        for (auto k = list_.wall_begin(i); k < list_.wall_end(i); ++k) {
            if (wall_touch_[k] != 0)
                out.push_back({ids_[i], wall_key(list_.wall(k)), wall_hist_[k], wall_roll_[k], wall_fn_[k],
                               wall_normal_[k]});
        }
    }
}

namespace {
// v becomes the values `field` takes from `grains`, followed by its entries from `old_mobile` on (the fixed
// spheres')
template <class T, class Field>
void replace_front(std::vector<T>& v, std::size_t old_mobile, std::span<const GrainRecord> grains,
                   Field field) {
    std::vector<T> fixed(v.begin() + static_cast<std::ptrdiff_t>(old_mobile), v.end());
    v.resize(grains.size());
    for (std::size_t k = 0; k < grains.size(); ++k) v[k] = field(grains[k]);
    v.insert(v.end(), fixed.begin(), fixed.end());
}
}  // namespace

void DemSolver::replace_mobile(std::span<const GrainRecord> grains, std::size_t ghosts,
                               std::vector<ContactRecord> contacts) {
    if (ghosts > grains.size())
        throw InputError(fmt::format("replace_mobile: {} ghosts among {} grains", ghosts, grains.size()));
    if (!gone_.empty()) throw InputError("replace_mobile: grains flagged for removal are still in the lists");
    const std::size_t old = p_.n_mobile;
    replace_front(p_.x, old, grains, [](const GrainRecord& g) { return g.x; });
    replace_front(p_.v, old, grains, [](const GrainRecord& g) { return g.vh; });  // a cache: re-derived
    replace_front(p_.w, old, grains, [](const GrainRecord& g) { return g.wh; });
    replace_front(p_.f, old, grains, [](const GrainRecord& g) { return g.f; });
    replace_front(p_.t, old, grains, [](const GrainRecord& g) { return g.t; });
    replace_front(p_.r, old, grains, [](const GrainRecord& g) { return g.r; });
    replace_front(p_.m, old, grains, [](const GrainRecord& g) { return g.m; });
    replace_front(p_.inv_m, old, grains, [](const GrainRecord& g) { return g.inv_m; });
    replace_front(p_.inv_j, old, grains, [](const GrainRecord& g) { return g.inv_j; });
    replace_front(vh_, old, grains, [](const GrainRecord& g) { return g.vh; });
    replace_front(wh_, old, grains, [](const GrainRecord& g) { return g.wh; });
    replace_front(ids_, old, grains, [](const GrainRecord& g) { return g.id; });
    replace_front(contact_count_, old, grains, [](const GrainRecord& g) {
        return static_cast<std::uint16_t>(std::min<std::uint32_t>(g.contacts, 65535));
    });
    if (external_) {
        external_force_.resize(grains.size());
        external_torque_.resize(grains.size());
        // a ghost's owner adds the fluid's force: its copy here holds none (its force here is the reactions
        // that go back to the owner)
        const std::size_t own = grains.size() - ghosts;
        for (std::size_t k = 0; k < grains.size(); ++k) {
            external_force_[k] = k < own ? grains[k].external_force : Vec3{};
            external_torque_[k] = k < own ? grains[k].external_torque : Vec3{};
        }
    }
    p_.n_mobile = grains.size();
    ghost_count_ = ghosts;
    const std::size_t n = p_.size();
    rolling_dm_.resize(n);
    parked_.assign(n, 1);
    recv_.assign(n, Received{});
    synced_ = false;
    // each grain pair seen from both grains, so that a list row finds all its histories in one run
    const std::size_t records = contacts.size();
    for (std::size_t c = 0; c < records; ++c)
        if (contacts[c].b < first_wall_key) contacts.push_back(mirrored(contacts[c]));
    std::sort(contacts.begin(), contacts.end(), before);
    carried_ = std::move(contacts);
    carry_by_id_ = true;
    lists_stale_ = true;
    partition_threads_ = 0;  // the blocks follow the new grains
}

void DemSolver::ghost_states(std::span<const std::uint32_t> indices, std::vector<GhostState>& out) const {
    out.clear();
    for (const std::uint32_t i : indices) out.push_back({p_.x[i], vh_[i], wh_[i], contact_count_[i]});
}

void DemSolver::set_ghost_states(std::span<const GhostState> states) {
    if (states.size() != ghost_count_)
        throw InputError(
            fmt::format("set_ghost_states: {} states for {} ghosts", states.size(), ghost_count_));
    const std::size_t first = own_count();
    for (std::size_t g = 0; g < states.size(); ++g) {
        p_.x[first + g] = states[g].x;
        vh_[first + g] = states[g].vh;
        wh_[first + g] = states[g].wh;
        contact_count_[first + g] = static_cast<std::uint16_t>(states[g].contacts);
    }
    synced_ = false;
}

void DemSolver::add_spin(std::size_t i, const Vec3& dw) {
    wh_[i] += dw;
    synced_ = false;
}

void DemSolver::add_reaction(std::size_t i, const Vec3& force, const Vec3& torque, std::uint32_t count) {
    p_.f[i] += force;
    p_.t[i] += torque;
    wh_[i] += dt_ * (p_.inv_j[i] * torque);
    contact_count_[i] = static_cast<std::uint16_t>(std::min<std::uint32_t>(contact_count_[i] + count, 65535));
    synced_ = false;
}

void DemSolver::set_wall_active(std::size_t wall, bool active) {
    walls_.at(wall).active = active;
    lists_stale_ = true;  // wall candidates depend on which walls are active
}

std::size_t DemSolver::memory_bytes() const {
    // x, v, w, f, t, vh, wh, rolling_dm; received reactions; r, m, 1/m, 1/J, half-skin; contact count,
    // parked flag
    const std::size_t per_particle = 8 * sizeof(Vec3) + sizeof(Received) + 5 * sizeof(double) +
                                     sizeof(std::uint16_t) + sizeof(std::uint8_t);
    const std::size_t pairs = pair_hist_.capacity() * sizeof(TangentialState) +
                              partner_reaction_.capacity() * sizeof(Reaction) +
                              (pair_fn_.capacity() + partner_fn_.capacity()) * sizeof(double) +
                              active_.capacity() * sizeof(std::uint32_t) + pair_touch_.capacity() +
                              pair_roll_.capacity() * sizeof(Vec3);
    const std::size_t wall_entries = wall_hist_.capacity() * sizeof(TangentialState) +
                                     wall_fn_.capacity() * sizeof(double) + wall_touch_.capacity() +
                                     (wall_roll_.capacity() + wall_normal_.capacity()) * sizeof(Vec3);
    const std::size_t prev =
        (prev_offset_.capacity() + prev_partner_.capacity() + prev_wall_offset_.capacity()) *
            sizeof(std::uint32_t) +
        (prev_pair_hist_.capacity() + prev_wall_hist_.capacity()) * sizeof(TangentialState) +
        (prev_pair_roll_.capacity() + prev_wall_roll_.capacity() + prev_wall_normal_.capacity()) *
            sizeof(Vec3);
    return p_.x.capacity() * per_particle + list_.bytes() + pairs + wall_entries + prev +
           wall_partial_.capacity() * sizeof(Vec3);
}

void DemSolver::synchronize() const {
    if (synced_) return;
    // v(t) = v(t − Δt/2) + Δt/2 (F/m + g);  ω(t) = ω(t + Δt/2) − Δt/2 T/J (ω is already kicked)
    const double h = 0.5 * dt_;
    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < nm; ++i) {
        p_.v[i] = vh_[i] + h * (p_.f[i] * p_.inv_m[i] + step_gravity_);
        p_.w[i] = wh_[i] - h * (p_.inv_j[i] * p_.t[i]);
    }
    synced_ = true;
}

KineticEnergy DemSolver::kinetic_energy() const {
    synchronize();
    return p_.kinetic_energies();
}

namespace {
// Energy of a tangential spring: k_t |ξ|²/2 while sticking; a slipping contact's spring also holds
// the dashpot force (Luding's reset), so only the Coulomb-limit part (μ_d F_n)²/(2 k_t) is elastic.
double tangential_energy(const LudingFriction& f, const TangentialState& s, double fn, double kt) {
    if (s.sliding != 0) {
        const double limit = f.mu_d * fn;
        return 0.5 * limit * limit / kt;
    }
    return 0.5 * kt * norm2(s.xi);
}
}  // namespace

double DemSolver::elastic_energy() const {
    return std::visit(
        [this](const auto& laws) {
            double u = 0.0;
            const std::size_t nm = p_.n_mobile;
            for (std::size_t i = 0; i < nm; ++i) {
                const double ri = p_.r[i];
                for (auto k = list_.begin(i); k < list_.end(i); ++k) {
                    const auto j = list_.partner(k);
                    const double rs = ri + p_.r[j], delta = rs - norm(p_.x[j] - p_.x[i]);
                    if (delta <= 0.0) continue;
                    const auto& law = j < nm ? laws.particle_particle : laws.particle_barrier;
                    const double r_eff = ri * p_.r[j] / rs;
                    u += law.normal.potential(delta, r_eff) +
                         tangential_energy(law.tangential, pair_hist_[k], pair_fn_[k],
                                           law.normal.tangential_stiffness(delta, r_eff));
                }
                for (auto k = list_.wall_begin(i); k < list_.wall_end(i); ++k) {
                    const Wall& wall = walls_[list_.wall(k)];
                    const auto& law = wall.barrier ? laws.particle_barrier : laws.particle_wall;
                    // a contact, with the spring of entry e (none: a fresh one)
                    const auto add = [&](const WallTouch& c, const std::uint32_t* e) {
                        u += law.normal.potential(c.delta, ri);
                        if (e != nullptr)
                            u += tangential_energy(law.tangential, wall_hist_[*e], wall_fn_[*e],
                                                   law.normal.tangential_stiffness(c.delta, ri));
                    };
                    if (wall.shape == WallShape::mesh) {  // each contact with the history of its slot
                        const MeshTouches now = mesh_touches(wall, list_.triangles(k), p_.x[i], ri);
                        const SlotChoice choice = assign_slots(now, {wall_normal_.data() + k, mesh_slots},
                                                               {wall_touch_.data() + k, mesh_slots});
                        for (std::uint32_t c = 0; c < now.count; ++c) {
                            const std::uint32_t e = k + choice.slot[c];
                            add(now.touch[c], choice.fresh[c] ? nullptr : &e);
                        }
                        k += mesh_slots - 1;
                        continue;
                    }
                    WallTouch c;
                    if (touches(wall, {}, p_.x[i], ri, c)) add(c, &k);
                }
            }
            return u;
        },
        laws_);
}

namespace {
// Grains are processed in fixed blocks: each block's wall reactions go to their own partial sums,
// which are added in block order, so the total does not depend on the thread count.
constexpr std::size_t block_size = 64;

std::size_t block_count(std::size_t n_mobile) {
    return (n_mobile + block_size - 1) / block_size;
}

// per-thread wall scratch rows, padded to whole cache lines apart (no false sharing)
std::size_t scratch_stride(std::size_t n_walls) {
    return (n_walls + 7) / 8 * 8 + 8;
}
}  // namespace

std::pair<std::size_t, std::size_t> DemSolver::grain_range(std::size_t t) const {
    return {block_bounds_[t] * block_size, std::min(p_.n_mobile, block_bounds_[t + 1] * block_size)};
}

void DemSolver::restored() {
    const std::size_t n = p_.size(), nm = p_.n_mobile, np = list_.pair_count(), nw = list_.walls().size();
    const auto sized = [](std::size_t size, const auto&... v) { return ((v.size() == size) && ...); };
    // the active entries of each block lie in its own run of entries (the rolling sweep visits them)
    const auto active_in_blocks = [&] {
        const auto& offset = list_.offsets();
        for (std::size_t b = 0; b < block_active_.size(); ++b) {
            const std::uint32_t first = offset[b * block_size],
                                last = offset[std::min(nm, (b + 1) * block_size)];
            if (block_active_[b] > last - first) return false;
            for (std::uint32_t a = 0; a < block_active_[b]; ++a)
                if (active_[first + a] < first || active_[first + a] >= last) return false;
        }
        return true;
    };
    const bool consistent =
        p_.n_mobile <= n &&
        sized(n, p_.v, p_.w, p_.f, p_.t, p_.r, p_.m, p_.inv_m, p_.inv_j, ids_, vh_, wh_, contact_count_) &&
        sized(np, pair_hist_, pair_fn_, pair_touch_, pair_roll_, active_, partner_reaction_, partner_fn_) &&
        sized(nw, wall_hist_, wall_roll_, wall_fn_, wall_touch_, wall_normal_) &&
        wall_force_.size() == walls_.size() && block_active_.size() == block_count(nm) &&
        (gone_.empty() || gone_.size() == nm) &&
        (external_ ? external_force_.size() == nm && external_torque_.size() == nm
                   : external_force_.empty()) &&
        ghost_count_ <= nm && list_.consistent(n, nm, walls_) && active_in_blocks();
    if (!consistent)
        throw InputError("the checkpoint's grain state does not fit together (corrupt checkpoint)");
    rolling_dm_.resize(n);
    parked_.assign(n, 1);
    recv_.assign(n, Received{});
    wall_push_.assign(nw, Vec3{});  // (the next force pass writes them)
    wall_triangle_.assign(nw, 0);
    partition_threads_ = 0;  // the partition follows the team that runs next
}

void DemSolver::add_triangle_forces(const geometry::TriangleMesh& mesh, std::span<Vec3> per_triangle) const {
    for (std::size_t i = 0; i < own_count(); ++i)
        for (auto k = list_.wall_begin(i); k < list_.wall_end(i); ++k) {
            const Wall& wall = walls_[list_.wall(k)];
            if (wall.shape != WallShape::mesh || wall.surface->mesh.get() != &mesh || wall_touch_[k] == 0)
                continue;
            per_triangle[wall_triangle_[k]] += wall_push_[k];
        }
}

int DemSolver::prepare_threads() {
    const int threads = omp_get_max_threads();
    if (partition_threads_ != threads) partition_blocks(threads);
    // every block writes its whole row and every thread clears its scratch row before use
    const std::size_t n_walls = walls_.size(), n_blocks = block_count(p_.n_mobile);
    wall_partial_.resize(n_blocks * n_walls);
    wall_scratch_.resize(static_cast<std::size_t>(threads) * scratch_stride(n_walls));
    return threads;
}

bool DemSolver::team_matches_partition() {
    if (omp_get_num_threads() == partition_threads_) return true;
#pragma omp atomic write
    team_mismatch_ = true;
    return false;
}

void DemSolver::partition_blocks(int threads) {
    // contiguous ranges of blocks with about equal work: list entries both ways and wall
    // candidates (cheap distance checks) plus active contacts of the last step (force evaluations)
    const std::size_t n_blocks = block_count(p_.n_mobile);
    std::vector<double>& cost = block_cost_;
    cost.assign(n_blocks + 1, 0.0);
    for (std::size_t b = 0; b < n_blocks; ++b) {
        double c = 0.0;
        for (std::size_t i = b * block_size; i < std::min(p_.n_mobile, (b + 1) * block_size); ++i) {
            c += 4.0 + (list_.end(i) - list_.begin(i)) + (list_.t_end(i) - list_.t_begin(i)) +
                 2.0 * (list_.wall_end(i) - list_.wall_begin(i)) + 6.0 * contact_count_[i];
        }
        cost[b + 1] = cost[b] + c;
    }
    // measured balance: blocks of a thread that took longer than its modelled share cost more, by
    // half the measured ratio (damped, the window between partitions can be short)
    if (threads > 1 && partition_threads_ == threads &&
        busy_.size() == static_cast<std::size_t>(threads) * busy_stride &&
        block_bounds_.size() == static_cast<std::size_t>(threads) + 1 && block_bounds_.back() == n_blocks) {
        double total_busy = 0.0;
        for (int t = 0; t < threads; ++t) total_busy += busy_[static_cast<std::size_t>(t) * busy_stride];
        if (total_busy > 0.0) {
            std::vector<double>& scaled = block_time_;
            scaled.assign(n_blocks + 1, 0.0);
            for (int t = 0; t < threads; ++t) {
                const std::size_t b0 = block_bounds_[static_cast<std::size_t>(t)],
                                  b1 = block_bounds_[static_cast<std::size_t>(t) + 1];
                const double modelled = (cost[b1] - cost[b0]) / cost[n_blocks];
                const double measured = busy_[static_cast<std::size_t>(t) * busy_stride] / total_busy;
                const double factor =
                    modelled > 0.0 && measured > 0.0 ? 0.5 + 0.5 * measured / modelled : 1.0;
                for (std::size_t b = b0; b < b1; ++b) scaled[b + 1] = (cost[b + 1] - cost[b]) * factor;
            }
            for (std::size_t b = 0; b < n_blocks; ++b) scaled[b + 1] += scaled[b];
            std::swap(cost, scaled);
        }
    }
    busy_.assign(static_cast<std::size_t>(threads) * busy_stride, 0.0);
    block_bounds_.assign(static_cast<std::size_t>(threads) + 1, n_blocks);
    block_bounds_[0] = 0;
    std::size_t b = 0;
    for (int t = 1; t < threads; ++t) {
        const double target = cost[n_blocks] * t / threads;
        while (b < n_blocks && cost[b] < target) ++b;
        block_bounds_[static_cast<std::size_t>(t)] = b;
    }
    // a grain is parked when some owner of its pairs lies in an earlier thread's range
    for (int t = 0; t < threads; ++t) {
        const auto [lo, hi] = grain_range(static_cast<std::size_t>(t));
        for (std::size_t i = lo; i < hi; ++i) {
            const std::uint32_t owner = list_.first_owner(i);
            parked_[i] = owner != NeighborList::no_owner && owner < lo ? 1 : 0;
        }
    }
    std::fill(parked_.begin() + static_cast<std::ptrdiff_t>(p_.n_mobile), parked_.end(), 1);
    parked_list_.clear();
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        if (parked_[i] != 0) parked_list_.push_back(static_cast<std::uint32_t>(i));
    }
    partition_threads_ = threads;
}

void DemSolver::rebuild_lists() {
    const ScopeSeconds timed(list_seconds_);
    // keep the old lists and histories, then look every new entry up in the old list of the same i
    list_.exchange_rows(prev_offset_, prev_partner_, prev_wall_offset_, prev_wall_);
    std::swap(prev_pair_hist_, pair_hist_);
    std::swap(prev_wall_hist_, wall_hist_);
    std::swap(prev_pair_roll_, pair_roll_);
    std::swap(prev_wall_roll_, wall_roll_);
    std::swap(prev_wall_normal_, wall_normal_);
    const bool had_lists = list_.builds() > 0 && !carry_by_id_;
    // a divided run's grains come in the order its halo gives them (ghosts last): no reordering here
    const bool sort = had_lists && ghost_count_ == 0 && reorder_interval_ > 0 &&
                      ++builds_since_reorder_ >= reorder_interval_;
    reordered_ = sort || !gone_.empty();
    removed_now_ = 0;
    if (reordered_) {
        renumber_grains(sort);
        if (sort) builds_since_reorder_ = 0;
    }

    // Each grain's half-skin: at least half the skin, wider for a fast grain so that it alone does not
    // force a rebuild for about steps_per_half_skin steps (a flow's fast few — grains falling past a
    // barrier — would otherwise rebuild the whole list every few steps), at most half of skin_max_
    const std::size_t nm_now = p_.n_mobile;
    half_skin_.resize(nm_now);
    const double h_min = 0.5 * skin_, h_max = 0.5 * skin_max_;
    const double reach_per_speed = steps_per_half_skin * dt_;
    const auto snm_now = static_cast<std::ptrdiff_t>(nm_now);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < snm_now; ++i)
        half_skin_[i] = std::clamp(std::sqrt(norm2(vh_[i])) * reach_per_speed, h_min, h_max);
    list_.build(p_, walls_, half_skin_, h_min, p_.n_mobile - ghost_count_);
    const std::size_t np = list_.pair_count(), nw = list_.walls().size();
    // every entry is written below, in parallel, in one pass (carried over or reset); capacity grows
    // by 1/8 beyond the need, not by resize()'s doubling (memory per grain)
    const auto size_to = [](auto& v, std::size_t size) {
        if (size > v.capacity()) v.reserve(size + size / 8);
        v.resize(size);
    };
    size_to(pair_hist_, np);
    size_to(partner_reaction_, np);  // written before it is read
    size_to(pair_fn_, np);
    size_to(partner_fn_, np);
    size_to(pair_touch_, np);
    size_to(pair_roll_, np);
    size_to(active_, np);
    block_active_.assign(block_count(p_.n_mobile), 0);
    size_to(wall_hist_, nw);
    size_to(wall_roll_, nw);
    size_to(wall_fn_, nw);
    size_to(wall_touch_, nw);
    size_to(wall_normal_, nw);
    wall_push_.assign(nw, Vec3{});
    wall_triangle_.assign(nw, 0);
    partition_blocks(omp_get_max_threads());

    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
    const auto snp = static_cast<std::ptrdiff_t>(np);
#pragma omp parallel
    {
#pragma omp for schedule(static) nowait
        for (std::ptrdiff_t t = 0; t < snp; ++t) partner_fn_[t] = 0.0;
#pragma omp for schedule(static)
        for (std::ptrdiff_t i = 0; i < nm; ++i) {
            const auto ui = static_cast<std::size_t>(i);
            // the same pair in the old lists: in the row of the lower old index (after a reorder the
            // owner may be the other grain: then the history is seen from it, with the sign flipped)
            const auto old_of = [&](std::uint32_t q) {
                if (!reordered_) return q;
                return static_cast<std::ptrdiff_t>(q) < nm ? order_[q]
                                                           : q + static_cast<std::uint32_t>(removed_now_);
            };
            const std::uint32_t io = old_of(static_cast<std::uint32_t>(ui));
            // the carried records of this row's grain (carry_by_id_)
            const auto mine =
                std::equal_range(carried_.begin(), carried_.end(), ContactRecord{ids_[ui], 0, {}, {}},
                                 [](const ContactRecord& p, const ContactRecord& q) { return p.a < q.a; });
            for (auto k = list_.begin(ui); k < list_.end(ui); ++k) {
                pair_fn_[k] = 0.0;
                pair_hist_[k] = TangentialState{};
                pair_roll_[k] = {};
                pair_touch_[k] = 0;
                if (carry_by_id_) {
                    Vec3 unused;
                    carry_record(mine.first, mine.second, ids_[list_.partner(k)], 0, pair_hist_[k],
                                 pair_roll_[k], pair_fn_[k], pair_touch_[k], unused);
                    continue;
                }
                if (!had_lists) continue;
                const std::uint32_t jo = old_of(list_.partner(k));
                const bool same = io < jo;
                const std::uint32_t row = same ? io : jo, want = same ? jo : io;
                const auto ob = prev_partner_.begin() + prev_offset_[row],
                           oe = prev_partner_.begin() + prev_offset_[row + 1];
                const auto it = std::lower_bound(ob, oe, want);  // old rows are sorted
                if (it == oe || *it != want) continue;
                const auto q = it - prev_partner_.begin();
                pair_hist_[k] = prev_pair_hist_[q];
                pair_roll_[k] = prev_pair_roll_[q];
                if (!same) {  // the spring and the rolling torque as seen from the new owner
                    pair_hist_[k].xi = -pair_hist_[k].xi;
                    pair_roll_[k] = -pair_roll_[k];
                }
                pair_touch_[k] = 1;  // re-evaluated (and reset if apart) at the next force pass
            }
            for (auto k = list_.wall_begin(ui); k < list_.wall_end(ui); ++k) {
                wall_hist_[k] = TangentialState{};
                wall_roll_[k] = {};
                wall_touch_[k] = 0;
                wall_fn_[k] = 0.0;
                wall_normal_[k] = {};
                // a mesh wall's slot: its place among the wall's entries in the row (the old row's entry
                // of the same place carries its history)
                std::uint32_t slot = 0;
                while (k - slot > list_.wall_begin(ui) && list_.wall(k - slot - 1) == list_.wall(k)) ++slot;
                if (carry_by_id_) {
                    carry_record(mine.first, mine.second, wall_key(list_.wall(k)), slot, wall_hist_[k],
                                 wall_roll_[k], wall_fn_[k], wall_touch_[k], wall_normal_[k]);
                    continue;
                }
                if (!had_lists) continue;
                for (auto q = prev_wall_offset_[io]; q < prev_wall_offset_[io + 1]; ++q) {
                    if (prev_wall_[q] != list_.wall(k)) continue;
                    q += slot;  // the same wall's entries are in a row
                    wall_hist_[k] = prev_wall_hist_[q];
                    wall_roll_[k] = prev_wall_roll_[q];
                    wall_normal_[k] = prev_wall_normal_[q];
                    wall_touch_[k] = 1;
                    break;
                }
            }
        }
    }
    if (carry_by_id_) {
        // the carried normal forces as the last force pass would have left them: the partners' copies and
        // each block's pushing entries, which the next rolling sweep visits (a force pass rewrites them)
        const auto& slot = list_.t_slots();
        for (std::size_t k = 0; k < np; ++k) partner_fn_[slot[k]] = pair_fn_[k];
        const auto& offset = list_.offsets();
        for (std::size_t b = 0; b < block_active_.size(); ++b) {
            const std::uint32_t first = offset[b * block_size],
                                last = offset[std::min(p_.n_mobile, (b + 1) * block_size)];
            std::uint32_t n = 0;
            for (std::uint32_t k = first; k < last; ++k)
                if (pair_fn_[k] > 0.0) active_[first + n++] = k;
            block_active_[b] = n;
        }
    }
    carry_by_id_ = false;
    carried_.clear();
}

void DemSolver::drop_last_reactions() {
    std::fill(p_.f.begin() + static_cast<std::ptrdiff_t>(p_.n_mobile), p_.f.end(), Vec3{});
    std::fill(p_.t.begin() + static_cast<std::ptrdiff_t>(p_.n_mobile), p_.t.end(), Vec3{});
    std::fill(wall_force_.begin(), wall_force_.end(), Vec3{});
    stats_ = {};
}

void DemSolver::rebuild_lists_now() {
    rebuild_lists();
    lists_stale_ = false;
}

void DemSolver::carry_record(std::vector<ContactRecord>::const_iterator first,
                             std::vector<ContactRecord>::const_iterator last, std::uint32_t b,
                             std::uint32_t ordinal, TangentialState& history, Vec3& rolling,
                             double& normal_force, std::uint8_t& touch, Vec3& normal) {
    for (auto it = first; it != last; ++it) {  // a few records: those of one grain
        if (it->b != b || ordinal-- > 0) continue;
        history = it->history;
        rolling = it->rolling;
        normal_force = it->normal_force;
        normal = it->normal;
        touch = 1;  // re-evaluated (and reset if apart) at the next force pass
        return;
    }
}

std::array<const WallTouch*, mesh_slots> DemSolver::place_in_slots(std::uint32_t k, const MeshTouches& now) {
    const SlotChoice choice =
        assign_slots(now, {wall_normal_.data() + k, mesh_slots}, {wall_touch_.data() + k, mesh_slots});
    std::array<const WallTouch*, mesh_slots> in_slot{};
    for (std::uint32_t c = 0; c < now.count; ++c) {
        const std::uint32_t e = k + choice.slot[c];
        in_slot[choice.slot[c]] = &now.touch[c];
        wall_normal_[e] = now.touch[c].n;
        if (choice.fresh[c]) {
            wall_hist_[e] = TangentialState{};
            wall_roll_[e] = {};
            wall_fn_[e] = 0.0;
        }
    }
    return in_slot;
}

void DemSolver::compute_forces() {
    if (lists_stale_ || list_.needs_rebuild(p_)) {
        rebuild_lists();
        lists_stale_ = false;
    }
    evaluate_forces(false);
}

void DemSolver::evaluate_forces(bool integrate) {
    ForceTotals totals;
    const int threads = prepare_threads();
    std::visit(
        [&](const auto& laws) {
#pragma omp parallel num_threads(threads)
            force_passes(laws, totals, integrate);
        },
        laws_);
    finish_forces(totals);
}

void DemSolver::finish_forces(const ForceTotals& totals) {
    if (team_mismatch_)
        throw RunError(
            "the OpenMP runtime gave a parallel region fewer threads than requested (nested "
            "parallelism or OMP_DYNAMIC?); run with OMP_DYNAMIC=false");
    if (totals.bad == 2)
        throw RunError(fmt::format("step {}, t = {:.6g} s: {} (the run blew up)", steps_, time_,
                                   first_non_finite_grain()));
    if (totals.bad == 1)
        throw RunError(fmt::format("step {}, t = {:.6g} s: two sphere centres coincide ({})", steps_, time_,
                                   largest_overlap_site()));
    const std::size_t n_walls = walls_.size();
    std::fill(wall_force_.begin(), wall_force_.end(), Vec3{});
    for (std::size_t b = 0; b * n_walls < wall_partial_.size(); ++b) {
        for (std::size_t w = 0; w < n_walls; ++w) wall_force_[w] += wall_partial_[b * n_walls + w];
    }
    stats_ = {totals.contacts, totals.sliding, totals.max_ratio};
    max_overlap_seen_ = std::max(max_overlap_seen_, totals.max_ratio);
}

// Per-grain finishing steps, inlined into the passes' grain loops (as calls they cost a seventh of
// the early window each: every call stored and reloaded its operands).
void DemSolver::finish_forces_of(std::size_t j, double fx, double fy, double fz, double tx, double ty,
                                 double tz, std::uint32_t own_count, const Received& recv, bool integrate) {
    Vec3 f = Vec3{fx, fy, fz} + recv.force, t = Vec3{tx, ty, tz} + recv.torque;
    if (external_) {  // not even + 0 in dry runs: a −0 force would print as "-0"
        f += external_force_[j];
        t += external_torque_[j];
    }
    p_.f[j] = f;
    p_.t[j] = t;
    contact_count_[j] = static_cast<std::uint16_t>(std::min<std::uint32_t>(own_count + recv.count, 65535));
    // ω is kicked to the next half step here (the rolling sweep needs it), v in the drift (so a gravity
    // change between steps acts at once); synchronize() derives v(t), ω(t) when they are asked for
    if (integrate) wh_[j] += dt_ * (p_.inv_j[j] * t);
}

// Returns how far the grain is past its half-skin (NeighborList::excess; 0 without drift).
[[gnu::always_inline]] inline double DemSolver::finish_sweep(std::size_t i, const Vec3& dm, bool drift) {
    wh_[i] += (dt_ * p_.inv_j[i]) * dm;
    if (!drift) return 0.0;
    vh_[i] += dt_ * (p_.f[i] * p_.inv_m[i] + gravity_);
    p_.x[i] += dt_ * vh_[i];
    // a ghost's drift is replaced by its owner's state; the owner tests its list validity
    return i < p_.n_mobile - ghost_count_ ? list_.excess(i, p_.x[i]) : 0.0;
}

// Runs inside a parallel region (every thread calls it): the passes are orphaned worksharing loops
// separated by their implicit barriers. Counters are merged under a critical section; they are
// integer sums and maxima, exact in any order.
template <class Normal>
void DemSolver::force_passes(const ContactLawSet<Normal>& laws, ForceTotals& totals, bool integrate) {
    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
    const auto n = static_cast<std::ptrdiff_t>(p_.size());
    const double dt = dt_;
    const std::size_t n_walls = walls_.size();
    const std::size_t stride = scratch_stride(n_walls);
    if (!team_matches_partition()) return;
    const auto me = static_cast<std::size_t>(omp_get_thread_num());
    const auto b_begin = static_cast<std::ptrdiff_t>(block_bounds_[me]);
    const auto b_end = static_cast<std::ptrdiff_t>(block_bounds_[me + 1]);
    const double t_pass1 = omp_get_wtime();
    Vec3* scratch = wall_scratch_.data() + static_cast<std::size_t>(omp_get_thread_num()) * stride;
    // local views: the compiler cannot prove the per-pair stores leave these untouched
    const Vec3* __restrict x = p_.x.data();
    const Vec3* __restrict vh = vh_.data();
    const Vec3* wh = wh_.data();  // interior grains are kicked during this pass
    const double* __restrict r = p_.r.data();
    const double* __restrict inv_m = p_.inv_m.data();
    const std::uint32_t* __restrict partner = list_.partners().data();
    const std::uint32_t* __restrict slot = list_.t_slots().data();
    const std::uint32_t* __restrict owner = list_.owners().data();
    constexpr std::uint32_t chunk = batch_capacity;  // list entries screened per batch
    std::uint64_t contacts = 0, sliding = 0;
    double max_ratio = 0.0;
    int bad = 0;

    // Pass 1: each mobile i evaluates its own pairs (j > i) and its wall contacts: normal and
    // tangential forces. The force on i is summed here; the reaction on j goes to j's Received record
    // or, if j is parked, to its transposed slot for pass 2; wall reactions go to the block's partial
    // sums. A grain that is not parked is complete at the end of its own iteration and finished there.
    for (std::ptrdiff_t b = b_begin; b < b_end; ++b) {
        std::fill(scratch, scratch + n_walls, Vec3{});
        const std::ptrdiff_t i_begin = b * static_cast<std::ptrdiff_t>(block_size);
        const std::ptrdiff_t i_end =
            std::min<std::ptrdiff_t>(nm, i_begin + static_cast<std::ptrdiff_t>(block_size));
        // The block's pair entries are one run of the list: they are screened and evaluated as one
        // sequence (no per-grain loops with short, unpredictable trip counts); each grain's own sums
        // are kept per block and still added in ascending entry order, then its walls.
        Vec3 f_own[block_size], t_own[block_size];
        std::uint32_t n_own[block_size];
        std::fill(f_own, f_own + block_size, Vec3{});
        std::fill(t_own, t_own + block_size, Vec3{});
        std::fill(n_own, n_own + block_size, 0U);
        const std::uint32_t k_first = list_.begin(static_cast<std::size_t>(i_begin));
        const std::uint32_t k_end = list_.end(static_cast<std::size_t>(i_end - 1));
        std::uint32_t n_active = 0;
        ContactBatch batch;
        for (std::uint32_t k0 = k_first; k0 < k_end; k0 += chunk) {
            // stage 1, branch-light so the partners' loads overlap: which entries overlap (a NaN
            // distance counts as overlapping and is caught below); contacts that opened lose
            // their history
            std::uint32_t hits[chunk];
            std::uint32_t n_hits = 0;
            const std::uint32_t k1 = std::min(k_end, k0 + chunk);
            for (std::uint32_t k = k0; k < k1; ++k) {
                const std::uint32_t i = owner[k], j = partner[k];
                const double rs = r[i] + r[j];
                const bool hit = !(norm2(x[j] - x[i]) >= rs * rs);
                hits[n_hits] = k;
                n_hits += hit ? 1U : 0U;
                // one rarely taken branch (a contact that opened this step) instead of a branch on
                // `hit`, which is unpredictable
                const unsigned opened = static_cast<unsigned>(!hit) & pair_touch_[k];
                if (opened != 0U) [[unlikely]] {
                    pair_hist_[k] = TangentialState{};
                    pair_roll_[k] = {};
                    pair_fn_[k] = 0.0;
                    partner_fn_[slot[k]] = 0.0;  // kept valid for every slot, parked or not
                    pair_touch_[k] = 0;
                }
            }
            // stage 2: the contacts, gathered into a batch and evaluated as one vector loop with the
            // particle–particle law (contact_batch.h); pairs with a fixed sphere are re-evaluated
            // with the barrier law from their unchanged history, then all are summed in list order
            for (std::uint32_t h = 0; h < n_hits; ++h) {
                const std::uint32_t k = hits[h];
                const std::uint32_t i = owner[k], j = partner[k];
                batch.d.set(h, x[j] - x[i]);
                batch.dv.set(h, vh[i] - vh[j]);
                batch.rw.set(h, r[i] * wh[i] + r[j] * wh[j]);
                batch.ri[h] = r[i];
                batch.rj[h] = r[j];
                batch.inv_m_sum[h] = inv_m[i] + inv_m[j];
                batch.set_state(h, pair_hist_[k], pair_roll_[k]);
            }
            evaluate(laws.particle_particle, batch, n_hits, dt);
            for (std::uint32_t h = 0; h < n_hits; ++h) {
                const std::uint32_t k = hits[h];
                const std::uint32_t i = owner[k], j = partner[k];
                if (batch.ok[h] == 0.0) {  // coincident centres, or NaN from a blown-up state
                    bad = std::max(bad, std::isnan(norm2(batch.d.get(h))) ? 2 : 1);
                    continue;
                }
                const double ri = r[i], rj = r[j];
                const bool mobile = static_cast<std::ptrdiff_t>(j) < nm;
                if (!mobile) [[unlikely]] {
                    batch.set_state(h, pair_hist_[k], pair_roll_[k]);
                    evaluate_lane(laws.particle_barrier, batch, h, dt);
                }
                const auto& law = mobile ? laws.particle_particle : laws.particle_barrier;
                const PairForce pf = batch.pair_force(h);
                const double delta = batch.delta[h];
                pair_hist_[k] = batch.state(h);
                // rolling torque: last step's, within the cap of the new normal force (warm start), or none
                Vec3 roll{};
                if (law.rolling.mu_r != 0.0) {
                    roll = batch.roll.get(h);
                    pair_roll_[k] = roll;
                }
                const std::size_t li = i - static_cast<std::size_t>(i_begin);
                f_own[li] += pf.force;
                t_own[li] += ri * pf.n_cross_ft + roll;
                // counted for both grains when it pushes (the contacts the rolling sweep visits and
                // splits the grain's inertia among), whichever grain's row holds it
                n_own[li] += pf.fn > 0.0 ? 1U : 0U;
                const std::uint32_t t = slot[k];
                partner_fn_[t] = pf.fn;
                if (parked_[j] != 0) {
                    partner_reaction_[t] = {pf.force, rj * pf.n_cross_ft - roll};
                } else if (pf.fn != 0.0) {  // as the gather: no normal force ⇒ nothing
                    Received& rcv = recv_[j];
                    rcv.force -= pf.force;
                    rcv.torque += rj * pf.n_cross_ft - roll;
                    rcv.count += pf.fn > 0.0 ? 1U : 0U;
                }
                pair_fn_[k] = pf.fn;
                active_[k_first + n_active] = k;  // kept if the sweep will visit it (branch-free)
                n_active += pf.fn <= 0.0 ? 0U : 1U;
                pair_touch_[k] = 1;
                ++contacts;  // the statistics count overlaps, pushing or not
                sliding += pair_hist_[k].sliding;
                max_ratio = std::max(max_ratio, delta / (2.0 * std::min(ri, rj)));
            }
        }
        block_active_[static_cast<std::size_t>(b)] = n_active;
        for (std::ptrdiff_t i = i_begin; i < i_end; ++i) {
            const std::size_t li = static_cast<std::size_t>(i - i_begin);
            const Vec3 xi = p_.x[i], vi = vh_[i], wi = wh_[i];
            const double ri = p_.r[i], inv_mi = p_.inv_m[i];
            Vec3 fi = f_own[li], ti = t_own[li];
            std::uint32_t count = n_own[li];
            // entry k's contact c (none: the entry's history is released)
            const auto wall_contact = [&](std::uint32_t k, const WallTouch* c) {
                if (c == nullptr) {
                    if (wall_touch_[k] != 0) {
                        wall_hist_[k] = TangentialState{};
                        wall_roll_[k] = {};
                        wall_fn_[k] = 0.0;
                        wall_touch_[k] = 0;
                    }
                    wall_push_[k] = {};
                    return;
                }
                const auto w = list_.wall(k);
                const auto& law = walls_[w].barrier ? laws.particle_barrier : laws.particle_wall;
                const PairForce pf =
                    pair_force(law, wall_hist_[k], c->n, c->delta, vi, ri * wi, 1.0 / inv_mi, ri, dt);
                Vec3 roll{};
                if (law.rolling.mu_r != 0.0) {
                    roll = law.rolling.start(wall_roll_[k], pf.fn, ri);
                    wall_roll_[k] = roll;
                }
                fi += pf.force;
                ti += ri * pf.n_cross_ft + roll;
                scratch[w] -= pf.force;
                wall_push_[k] = -pf.force;
                wall_triangle_[k] = c->triangle;
                wall_fn_[k] = pf.fn;
                wall_touch_[k] = 1;
                count += pf.fn > 0.0 ? 1U : 0U;
                ++contacts;
                sliding += wall_hist_[k].sliding;
                max_ratio = std::max(max_ratio, c->delta / (2.0 * ri));
            };
            for (auto k = list_.wall_begin(i); k < list_.wall_end(i);) {
                const Wall& wall = walls_[list_.wall(k)];
                if (wall.shape == WallShape::mesh) {  // its slots k .. k + mesh_slots − 1
                    const MeshTouches now = mesh_touches(wall, list_.triangles(k), xi, ri);
                    const std::array<const WallTouch*, mesh_slots> in_slot = place_in_slots(k, now);
                    for (std::uint32_t s = 0; s < mesh_slots; ++s) wall_contact(k + s, in_slot[s]);
                    k += mesh_slots;
                    continue;
                }
                WallTouch c;
                wall_contact(k, touches(wall, {}, xi, ri, c) ? &c : nullptr);
                ++k;
            }
            if (parked_[i] != 0) {  // finished by the gather
                p_.f[i] = fi;
                p_.t[i] = ti;
                contact_count_[i] = static_cast<std::uint16_t>(std::min<std::uint32_t>(count, 65535));
            } else {  // every owner of its pairs came before it in this thread: finish it now
                finish_forces_of(static_cast<std::size_t>(i), fi.x, fi.y, fi.z, ti.x, ti.y, ti.z, count,
                                 recv_[i], integrate);
                recv_[i] = Received{};
            }
        }
        std::copy(scratch, scratch + n_walls,
                  wall_partial_.begin() + b * static_cast<std::ptrdiff_t>(n_walls));
    }
    double busy = omp_get_wtime() - t_pass1;
#pragma omp critical(sabo_force_totals)
    {
        totals.contacts += contacts;
        totals.sliding += sliding;
        totals.max_ratio = std::max(totals.max_ratio, max_ratio);
        totals.bad = std::max(totals.bad, bad);
    }
#pragma omp barrier

    // Pass 2: parked grains gather their reactions in the fixed order of the transposed index, shared
    // out over all threads (each grain's sum is independent of who computes it), then the fixed spheres.
    busy_[me * busy_stride] += busy;
    const auto n_parked = static_cast<std::ptrdiff_t>(parked_list_.size());
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t q = 0; q < n_parked; ++q) gather_reactions(parked_list_[q], integrate);
#pragma omp for schedule(static)
    for (std::ptrdiff_t j = nm; j < n; ++j) gather_reactions(j, false);
}

void DemSolver::gather_reactions(std::ptrdiff_t j, bool integrate) {
    Received recv;  // summed from zero in ascending slot (= owner) order, as the in-pass scatter does
    for (auto t = list_.t_begin(j); t < list_.t_end(j); ++t) {
        if (partner_fn_[t] == 0.0) continue;  // no normal force ⇒ no friction either
        recv.force -= partner_reaction_[t].force;
        recv.torque += partner_reaction_[t].torque_j;
        recv.count += partner_fn_[t] > 0.0 ? 1U : 0U;
    }
    const auto uj = static_cast<std::size_t>(j);
    if (uj < p_.n_mobile) {
        const Vec3 f = p_.f[uj], t = p_.t[uj];
        finish_forces_of(uj, f.x, f.y, f.z, t.x, t.y, t.z, contact_count_[uj], recv, integrate);
    } else {
        p_.f[uj] = recv.force;
        p_.t[uj] = recv.torque;
        contact_count_[uj] = static_cast<std::uint16_t>(std::min<std::uint32_t>(recv.count, 65535));
    }
}

// Rolling resistance (docs/dem.md) as capped constraint torques (docs/dem.md, "rolling resistance").
// Each contact keeps its torque M from the last step; pass 1 clamped it to the new cap μ_r F_n A_r
// and it already acted in the ω kick. A sweep moves every M towards the torque that stops ω_rel over
// the step (mass-split projected Jacobi: ConstantTorqueRolling::update); the change is applied to
// ω_half before the drift, so the contact kinematics of the next evaluation see it. While a contact
// rolls, M stays at the cap opposing ω_rel; in a static deposit the warm start carries the converged
// torques from step to step and the grains stay exactly at rest.
// Each pair is updated once, by the grain that owns the list entry, from velocities that no sweep
// has changed yet; partners collect their share after a barrier: thread-count independent.
template <class Normal>
void DemSolver::sweep_pass(const ContactLawSet<Normal>& laws, bool rolling, bool drift, double& max_excess) {
    const auto nm = static_cast<std::ptrdiff_t>(p_.n_mobile);
    const double dt = dt_;
    if (!team_matches_partition()) return;
    const auto me = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t i_end = grain_range(me).second;
    const std::uint32_t* __restrict slot = list_.t_slots().data();
    const std::uint32_t* __restrict owner = list_.owners().data();
    const std::uint32_t* __restrict partner = list_.partners().data();
    const double t_start = omp_get_wtime();
    double excess = 0.0;  // local: a reference could alias the per-grain stores
    for (std::size_t b = block_bounds_[me]; b < block_bounds_[me + 1]; ++b) {
        const std::size_t b_first = b * block_size, b_end = std::min(i_end, b_first + block_size);
        // the block's contacts as one sequence (see force_passes); each grain's own corrections are
        // summed per block in ascending entry order, then its walls
        Vec3 dm_own[block_size];
        std::fill(dm_own, dm_own + block_size, Vec3{});
        RollingBatch rb;
        if (rolling) {
            const std::uint32_t k_first = list_.begin(b_first);
            const std::uint32_t* act = active_.data() + k_first;
            // in batches: gathered, updated as one vector loop (contact_batch.h), summed in order
            for (std::uint32_t a0 = 0; a0 < block_active_[b]; a0 += batch_capacity) {
                const std::uint32_t n = std::min(batch_capacity, block_active_[b] - a0);
                for (std::uint32_t h = 0; h < n; ++h) {
                    const std::uint32_t k = act[a0 + h];
                    const std::uint32_t i = owner[k], j = partner[k];
                    const auto& law =
                        static_cast<std::ptrdiff_t>(j) < nm ? laws.particle_particle : laws.particle_barrier;
                    rb.m.set(h, pair_roll_[k]);
                    rb.w_rel.set(h, wh_[i] - wh_[j]);
                    rb.split_inv_j[h] = contact_count_[i] * p_.inv_j[i] + contact_count_[j] * p_.inv_j[j];
                    rb.ri[h] = p_.r[i];
                    rb.rj[h] = p_.r[j];
                    rb.fn[h] = pair_fn_[k];
                    rb.mu_r[h] = law.rolling.mu_r;
                }
                update(rb, n, dt);
                for (std::uint32_t h = 0; h < n; ++h) {
                    const std::uint32_t k = act[a0 + h];
                    const std::uint32_t i = owner[k], j = partner[k];
                    Vec3 d{};
                    if (rb.mu_r[h] != 0.0) {
                        const Vec3 m = rb.m.get(h);
                        d = m - pair_roll_[k];
                        pair_roll_[k] = m;
                    }
                    dm_own[i - b_first] += d;
                    if (static_cast<std::ptrdiff_t>(j) >= nm) continue;  // fixed spheres do not rotate
                    if (parked_[j] != 0) {
                        partner_reaction_[slot[k]].torque_j = d;  // −d acts on the partner
                    } else {
                        recv_[j].torque -= d;  // the sweep's use of the record (see Received)
                    }
                }
            }
        }
        for (std::size_t ui = b_first; ui < b_end; ++ui) {
            Vec3 dm = dm_own[ui - b_first];
            for (auto k = list_.wall_begin(ui); rolling && k < list_.wall_end(ui); ++k) {
                if (wall_fn_[k] <= 0.0) continue;
                const auto& law = walls_[list_.wall(k)].barrier ? laws.particle_barrier : laws.particle_wall;
                if (law.rolling.mu_r == 0.0) continue;
                const double split_i = contact_count_[ui] * p_.inv_j[ui];
                const Vec3 m = ConstantTorqueRolling::update(wall_roll_[k], wh_[ui], split_i, dt,
                                                             law.rolling.cap(wall_fn_[k], p_.r[ui]));
                dm += m - wall_roll_[k];
                wall_roll_[k] = m;
            }
            if (parked_[ui] != 0) {
                rolling_dm_[ui] = dm;
            } else {  // its owners came before it in this thread: every correction is in
                excess = std::max(excess, finish_sweep(ui, dm + recv_[ui].torque, drift));
                recv_[ui].torque = {};
            }
        }
    }
    busy_[me * busy_stride] += omp_get_wtime() - t_start;
#pragma omp barrier
    // parked grains, shared out over all threads (each one's sum is independent of who computes it)
    const auto n_parked = static_cast<std::ptrdiff_t>(parked_list_.size());
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t q = 0; q < n_parked; ++q) {
        const std::size_t ui = parked_list_[static_cast<std::size_t>(q)];
        Vec3 recv{};
        if (rolling) {
            for (auto t = list_.t_begin(ui); t < list_.t_end(ui); ++t) {
                if (partner_fn_[t] > 0.0) recv -= partner_reaction_[t].torque_j;
            }
        }
        excess = std::max(excess, finish_sweep(ui, rolling_dm_[ui] + recv, drift));
    }
    max_excess = std::max(max_excess, excess);
#pragma omp barrier
}

// One leapfrog step (velocity Verlet with the two half kicks of consecutive steps merged):
// rolling sweep(s) on ω_half, kick v and drift x, forces at the new positions, then ω kicked to the
// next half step (force_passes); synchronous velocities are derived on demand (synchronize()).
void DemSolver::step() {
    const double excess = drift();
    finish_step(list_.needs_rebuild(excess));
}

double DemSolver::drift() {
    synced_ = false;  // v and ω change below
    double excess = 0.0;
    const bool rolling = std::visit(
        [](const auto& laws) {
            return laws.particle_particle.rolling.mu_r != 0.0 || laws.particle_wall.rolling.mu_r != 0.0 ||
                   laws.particle_barrier.rolling.mu_r != 0.0;
        },
        laws_);
    const int threads = prepare_threads();
    std::visit(
        [&](const auto& laws) {
#pragma omp parallel num_threads(threads)
            {
                double my_excess = 0.0;
                for (int sweep = 1; sweep < rolling_sweeps_ && rolling; ++sweep)
                    sweep_pass(laws, true, false, my_excess);
                sweep_pass(laws, rolling, true, my_excess);
#pragma omp critical(sabo_moved)
                excess = std::max(excess, my_excess);
            }
        },
        laws_);
    return excess;
}

void DemSolver::finish_step(bool rebuild) {
    // the constructor built the lists, so every grain has a reference position for its excess
    if (lists_stale_ || rebuild) {
        rebuild_lists();
        lists_stale_ = false;
    } else if (steps_ % 50 == 0) {
        partition_blocks(omp_get_max_threads());  // follow where the contacts are
    }
    evaluate_forces(true);
    step_gravity_ = gravity_;
    synced_ = false;
    ++steps_;
    time_ = static_cast<double>(steps_) * dt_;  // no drift from summing dt
    if (!std::isfinite(stats_.max_overlap_ratio))
        throw RunError(fmt::format("step {}, t = {:.6g} s: {} (the run blew up)", steps_, time_,
                                   first_non_finite_grain()));
    if (stats_.max_overlap_ratio > overlap_limit_) {
        throw RunError(fmt::format(
            "step {}, t = {:.6g} s: overlap reached {:.0f} % of a diameter (limit {:.0f} %, "
            "dem.max_overlap_over_d): {} — the time step is too large for the contact stiffness, or grains "
            "were generated overlapping",
            steps_, time_, 100.0 * stats_.max_overlap_ratio, 100.0 * overlap_limit_, largest_overlap_site()));
    }
}

std::string DemSolver::largest_overlap_site() const {
    const auto name = [&](std::size_t i) {
        return i < p_.n_mobile ? fmt::format("grain {}", ids_[i])
                               : fmt::format("fixed sphere {}", i - p_.n_mobile);
    };
    double worst = -std::numeric_limits<double>::infinity();
    std::string site = "no contact found";
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        const Vec3 xi = p_.x[i];
        for (auto k = list_.begin(i); k < list_.end(i); ++k) {
            const std::size_t j = list_.partner(k);
            const double ratio =
                (p_.r[i] + p_.r[j] - std::sqrt(norm2(p_.x[j] - xi))) / (2.0 * std::min(p_.r[i], p_.r[j]));
            if (ratio > worst) {
                worst = ratio;
                site = fmt::format("{} and {} at ({:.3f}, {:.3f}, {:.3f}) m", name(i), name(j), xi.x, xi.y,
                                   xi.z);
            }
        }
        for (auto k = list_.wall_begin(i); k < list_.wall_end(i); ++k) {
            const Wall& wall = walls_[list_.wall(k)];
            const double ratio = -clearance(wall, list_.triangles(k), xi, p_.r[i]) / (2.0 * p_.r[i]);
            if (ratio > worst) {
                worst = ratio;
                site = fmt::format("{} and wall '{}' at ({:.3f}, {:.3f}, {:.3f}) m", name(i), wall.name, xi.x,
                                   xi.y, xi.z);
            }
        }
    }
    return site;
}

void DemSolver::check_finite() const {
    double sum = 0.0;  // a NaN or an infinity anywhere makes the sum non-finite
    for (std::size_t i = 0; i < p_.n_mobile; ++i)
        sum += p_.x[i].x + p_.x[i].y + p_.x[i].z + p_.v[i].x + p_.v[i].y + p_.v[i].z + p_.w[i].x + p_.w[i].y +
               p_.w[i].z;
    if (!std::isfinite(sum))
        throw RunError(fmt::format("step {}, t = {:.6g} s: {} (the run blew up)", steps_, time_,
                                   first_non_finite_grain()));
}

void DemSolver::check_inside(const Vec3& lo, const Vec3& hi) const {
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        const Vec3& x = p_.x[i];
        const double r = p_.r[i];
        if (x.x >= lo.x - r && x.x <= hi.x + r && x.y >= lo.y - r && x.y <= hi.y + r && x.z >= lo.z - r &&
            x.z <= hi.z + r)
            continue;
        throw RunError(fmt::format(
            "step {}, t = {:.6g} s: grain {} left the domain: its centre is at ({:.4g}, {:.4g}, {:.4g}) m, "
            "outside [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] m by more than its radius, "
            "moving "
            "at {:.4g} m/s: it passed through a wall in one step (a smaller step: raise "
            "dem.steps_per_contact or "
            "reduce dem.dt_s; or stiffen the contacts)",
            steps_, time_, ids_[i], x.x, x.y, x.z, lo.x, hi.x, lo.y, hi.y, lo.z, hi.z, norm(p_.v[i])));
    }
}

std::string DemSolver::first_non_finite_grain() const {
    const auto finite = [](const Vec3& a) {
        return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
    };
    for (std::size_t i = 0; i < p_.n_mobile; ++i) {
        if (!finite(p_.x[i]) || !finite(p_.v[i]) || !finite(p_.w[i]))
            return fmt::format("grain {} has a non-finite position or velocity", ids_[i]);
    }
    return "a contact's distance is not finite";
}

}  // namespace sabo::dem
