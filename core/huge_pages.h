// Transparent huge pages for the whole process's large allocations.
//
// A 960x1080 frame allocates, per eye, G-buffer read-backs, rebuilt hits and images of
// ~95 MB each, and llvmpipe and Embree allocate as much again. With 4 KiB pages the first
// touch of each costs a page fault: ~400 000 of them in `photovr render --scene atrium`,
// 3-12 us each on the Firecracker VMs these figures come from (a 256 MiB first touch:
// 760 ms with 4 KiB pages, 22-27 ms on 2 MiB pages; bare metal pays less, but still pays
// to fault and zero page by page). Where the kernel gives huge pages only on request
// (/sys/kernel/mm/transparent_hugepage/enabled is "madvise", Debian's default), glibc's
// malloc requests them when its tunable glibc.malloc.hugetlb=1 is set (glibc >= 2.35).
// Tunables are read when the process starts, so the program re-executes itself once with
// it set. That covers every allocator built on malloc: ours, llvmpipe's, Embree's, OIIO's.
// What it costs: the dynamic loader's work once more (~0.1 s here), before the
// libraries' initialisers run.
#pragma once

#include <string>

namespace photovr {

// The GLIBC_TUNABLES value that asks malloc for huge pages, given the current value (null:
// unset) and the first line of the kernel's policy file; empty when that would not help
// (the policy is not "[madvise]", or the tunable is already there).
std::string tunablesWithHugePages(const char* current, const std::string& kernelPolicy);

// Re-executes the running program (/proc/self/exe, same arguments) with
// tunablesWithHugePages' value unless it is empty or PHOTOVR_HUGE_PAGES is set
// (PHOTOVR_HUGE_PAGES=0 opts out, e.g. under a debugger; the re-executed process sees 1).
// Returns when nothing is to be done or the exec failed. Runs from the executable's
// .preinit_array (PHOTOVR_PREINIT), before any shared library's initialiser: the
// 270 libraries OpenImageIO brings cost ~0.4 s to initialise here, which a re-exec from
// main() would pay twice.
void useHugePagesForMalloc(int argc, char** argv, char** envp);

// In one source file of an executable: call fn(argc, argv, envp) before anything else
// runs, e.g. useHugePagesForMalloc or a filter in front of it.
#define PHOTOVR_PREINIT(fn)                                                             \
  __attribute__((section(".preinit_array"), used)) static void (*const photovrPreinit)( \
      int, char**, char**) = fn

// Whether this process started with malloc asking for huge pages (for the log).
bool mallocUsesHugePages();

}  // namespace photovr
