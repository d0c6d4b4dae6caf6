// How the process's heap hands out and takes back host memory.
#pragma once
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <climits>

namespace rcsplat {

// Keeps freed memory in the process for the next allocation instead of handing it back to the kernel. By default glibc
// maps large blocks on their own (every block over 32 MB, smaller ones until its threshold has grown) and unmaps them
// when freed, so each of a frame's large host buffers (downloads, image layers, photon rounds: about 0.5 GB at
// 1920 x 1080) was fresh pages, whose faults cost more than the copies into them (4 KB pages: 0.6 ms a MB on the 2-core
// VM; benchmarks/RESULTS.md "Issue 13, thirteenth step"). Huge pages are no way out: the first touch of each in a new
// process waited on the kernel's compaction for up to 1.5 s. Memory stays the process's until it exits, and a freed
// block that later requests cannot use stays resident (the H100 machine's peak rose 18%), which suits a renderer that
// makes one frame, or a benchmark's frames of one size, per process. A no-op outside glibc, and under sanitizers,
// whose allocator ignores it.
inline void keep_freed_host_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);             // every block from the heap, where freed memory is reused...
  mallopt(M_TRIM_THRESHOLD, INT_MAX);  // ... and not returned while it is less than 2 GB
#endif
}

}  // namespace rcsplat
