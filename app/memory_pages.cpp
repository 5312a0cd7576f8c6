// The allocator's settings, read by jemalloc at start-up from this global
// (jemalloc's documented `malloc_conf`; RADIANT_JEMALLOC: CMakeLists.txt).
//
// Why jemalloc, and why transparent huge pages: a large scene's solve fills
// and frees a few GB of vectors (a 10⁶-triangle model's mesh, trees, node
// values and ray deposits). Each 4 KiB page is zeroed by the kernel at its
// first touch; on the small virtual machines we measure on, such a page
// fault costs about 11 µs, so glibc's malloc — which returns every large
// block to the kernel when it is freed, and faults it in again at the next
// allocation — spent seconds in the kernel (cornell-sphere-1m: 32.0 s whole
// run; 23.8 s with this). jemalloc keeps freed memory for reuse and, with
// "thp:always", asks the kernel for 2 MiB pages (one fault each) where
// Linux allows transparent huge pages on request (the default, "madvise").
// docs/PERFORMANCE.md has the measurements.
#ifdef RADIANT_JEMALLOC
extern "C" {
// NOLINTNEXTLINE: the name and type are jemalloc's interface.
const char *malloc_conf = "thp:always,metadata_thp:always";
}
#endif
