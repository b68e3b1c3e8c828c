// SPDX-License-Identifier: MIT
#include "io/checkpoint.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "core/error.h"

namespace sabo::io {

CheckpointOut::CheckpointOut(std::filesystem::path path) : path_(std::move(path)) {
    tmp_ = path_;
    tmp_ += ".tmp";
    file_ = std::fopen(tmp_.c_str(), "wb");
    if (file_ == nullptr)
        throw RunError(fmt::format("cannot write checkpoint {}: {}", tmp_.string(), std::strerror(errno)));
    bytes(checkpoint_magic, sizeof checkpoint_magic);
}

CheckpointOut::~CheckpointOut() {
    if (file_ != nullptr) {  // not committed: leave the previous checkpoint as it was
        std::fclose(file_);
        std::error_code ignored;
        std::filesystem::remove(tmp_, ignored);
    }
}

void Checksum::add(const void* data, std::size_t size) {
    const auto* b = static_cast<const unsigned char*>(data);
    while (size > 0 && tail_size_ > 0 && tail_size_ < 8) {  // complete the word begun before
        tail_[tail_size_++] = *b++;
        --size;
        if (tail_size_ == 8) {
            std::uint64_t w = 0;
            std::memcpy(&w, tail_, 8);
            mix(w);
            tail_size_ = 0;
        }
    }
    for (; size >= 8; size -= 8, b += 8) {
        std::uint64_t w = 0;
        std::memcpy(&w, b, 8);
        mix(w);
    }
    for (; size > 0; --size) tail_[tail_size_++] = *b++;
}

std::uint64_t Checksum::value() const {
    Checksum c = *this;
    if (c.tail_size_ > 0) {
        std::uint64_t w = 0;
        std::memcpy(&w, c.tail_, c.tail_size_);
        c.mix(w ^ (static_cast<std::uint64_t>(c.tail_size_) << 56));
    }
    return c.hash_;
}

void verify_checksum(const std::filesystem::path& path) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    std::FILE* f = ec ? nullptr : std::fopen(path.c_str(), "rb");
    if (f == nullptr) throw InputError(fmt::format("cannot read checkpoint {}", path.string()));
    Checksum sum;
    std::uint64_t stored = 0;
    bool whole = size >= sizeof checkpoint_magic + sizeof stored;
    std::vector<unsigned char> chunk(1 << 20);
    for (std::uintmax_t left = whole ? size - sizeof stored : 0; left > 0 && whole;) {
        const std::size_t n = std::min<std::uintmax_t>(left, chunk.size());
        whole = std::fread(chunk.data(), 1, n, f) == n;
        sum.add(chunk.data(), n);
        left -= n;
    }
    whole = whole && std::fread(&stored, 1, sizeof stored, f) == sizeof stored;
    std::fclose(f);
    if (!whole) throw InputError(fmt::format("{}: not a sabo checkpoint (too short)", path.string()));
    if (stored != sum.value())
        throw InputError(fmt::format(
            "{}: damaged checkpoint (its checksum does not match its content: written by another version, "
            "cut short or changed since)",
            path.string()));
}

void CheckpointOut::bytes(const void* data, std::size_t size) {
    if (size > 0 && std::fwrite(data, 1, size, file_) != size)
        throw RunError(fmt::format("writing checkpoint {} failed: {}", tmp_.string(), std::strerror(errno)));
    sum_.add(data, size);
}

void CheckpointOut::put(const std::string& s) {
    put(static_cast<std::uint64_t>(s.size()));
    bytes(s.data(), s.size());
}

namespace {

// Fault injection for the kill tests (tests/scripts/check_resume.py): with SABO_TEST_KILL_AT_CHECKPOINT=N
// the process kills itself (SIGKILL, as a machine stop would) in the N-th checkpoint written, after its
// bytes and before the rename.
void kill_if_asked() {
    static int written = 0;
    static const char* at = std::getenv("SABO_TEST_KILL_AT_CHECKPOINT");
    if (at != nullptr && ++written == std::atoi(at)) std::raise(SIGKILL);
}

}  // namespace

void CheckpointOut::commit() {
    const std::uint64_t sum = sum_.value();
    bytes(&sum, sizeof sum);
    // on the disk before it replaces the previous one: a power cut after the rename finds it whole
    bool ok = std::fflush(file_) == 0 && ::fsync(::fileno(file_)) == 0;
    int reason = errno;
    kill_if_asked();
    if (std::fclose(file_) != 0 && ok) {
        ok = false;
        reason = errno;
    }
    file_ = nullptr;
    if (!ok) {  // the previous checkpoint stays; the partial one goes
        std::error_code ignored;
        std::filesystem::remove(tmp_, ignored);
        throw RunError(fmt::format("writing checkpoint {} failed: {}", tmp_.string(), std::strerror(reason)));
    }
    std::filesystem::rename(tmp_, path_);
    const std::filesystem::path dir = path_.has_parent_path() ? path_.parent_path() : ".";
    if (const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY); fd >= 0) {  // the rename itself
        ::fsync(fd);
        ::close(fd);
    }
}

CheckpointIn::CheckpointIn(std::filesystem::path path) : path_(std::move(path)) {
    std::error_code ec;
    const auto size = std::filesystem::file_size(path_, ec);
    file_ = ec ? nullptr : std::fopen(path_.c_str(), "rb");
    if (file_ == nullptr) throw InputError(fmt::format("cannot read checkpoint {}", path_.string()));
    char magic[sizeof checkpoint_magic];
    if (size < sizeof magic + sizeof(std::uint64_t))
        throw InputError(fmt::format("{}: not a sabo checkpoint (too short)", path_.string()));
    left_ = sizeof magic;
    bytes(magic, sizeof magic);
    if (std::memcmp(magic, checkpoint_magic, sizeof magic) != 0)
        throw InputError(
            fmt::format("{}: not a sabo checkpoint of this version (written by another kind or version of "
                        "sabo?)",
                        path_.string()));
    verify_checksum(path_);
    left_ = size - sizeof magic - sizeof(std::uint64_t);  // the content, without the checksum
}

CheckpointIn::~CheckpointIn() {
    if (file_ != nullptr) std::fclose(file_);
}

void CheckpointIn::bytes(void* data, std::size_t size) {
    if (size > left_ || (size > 0 && std::fread(data, 1, size, file_) != size))
        throw InputError(fmt::format("{}: truncated checkpoint", path_.string()));
    left_ -= size;
}

std::uint64_t CheckpointIn::count(std::size_t bytes) {
    std::uint64_t n = 0;
    get(n);
    if (n > left_ / bytes)
        throw InputError(fmt::format("{}: corrupt checkpoint (a list longer than the file)", path_.string()));
    return n;
}

void CheckpointIn::get(std::string& s) {
    s.resize(count());
    bytes(s.data(), s.size());
}

void CheckpointIn::expect_end() {
    if (left_ != 0)
        throw InputError(
            fmt::format("{}: {} bytes more than this build's checkpoint holds (another version?)",
                        path_.string(), left_));
}

std::string case_identity(const Config& cfg) {
    std::istringstream in(cfg.resolved_toml());
    std::string line, identity;
    while (std::getline(in, line))
        if (!line.starts_with("end_time_s") && !line.starts_with("checkpoint_interval") &&
            !line.starts_with("progress_interval") && !line.starts_with("#") &&
            !line.starts_with("device =") && !line.starts_with("opencl_") &&
            !line.starts_with("dir ="))  // output.dir: where the run is, not what it is (a resume names it)
            identity += line + '\n';
    return identity;
}

void check_same_case(const std::filesystem::path& checkpoint, const std::string& stored,
                     const std::string& current) {
    if (stored == current) return;
    std::istringstream a(stored), b(current);
    std::string la, lb, table, found_a, found_b, found_table;
    while (std::getline(a, la) && std::getline(b, lb)) {
        if (la.starts_with("[")) table = la;
        if (la == lb || (!found_a.empty() && table == "[derived]")) continue;
        if (found_a.empty() || found_table == "[derived]") {
            found_a = la;
            found_b = lb;
            found_table = table;
            if (table != "[derived]") break;
        }
    }
    throw InputError(
        fmt::format("{} was written for another case: in {} it has '{}', this case '{}' (a resumed "
                    "run may change case.end_time_s, the checkpoint and progress intervals and the lattice's "
                    "device only)",
                    checkpoint.string(), found_table.empty() ? "the case" : found_table, found_a, found_b));
}

}  // namespace sabo::io
