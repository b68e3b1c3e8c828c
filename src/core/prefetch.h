// SPDX-License-Identifier: MIT
// Software prefetch that the compiler keeps. GCC vectorises a loop whose body is only __builtin_prefetch
// calls into nothing (and drops them in loops it vectorises), so on x86-64 the instruction is emitted
// directly.
#pragma once

namespace sabo {

// the cache line holding *p, for reading
inline void prefetch_read(const void* p) {
#if defined(__x86_64__)
    asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#else
    __builtin_prefetch(p, 0, 3);
#endif
}

// the cache line holding *p, to be written (prefetchw where the CPU has it, else as for reading)
inline void prefetch_write(const void* p) {
#if defined(__x86_64__) && defined(__PRFCHW__)
    asm volatile("prefetchw %0" : : "m"(*static_cast<const char*>(p)));
#else
    prefetch_read(p);
#endif
}

}  // namespace sabo
