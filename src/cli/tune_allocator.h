// The C library's allocator, set for hullmesh's pattern: whole-mesh arrays of megabytes, built
// and freed stage after stage.
#pragma once

namespace hm::cli {

// Call first in main, with main's argv. With glibc on Linux, and unless GLIBC_TUNABLES already
// sets a malloc tunable or HULLMESH_DEFAULT_ALLOCATOR is set, the program runs itself again
// (execv of /proc/self/exe, the same arguments) with transparent huge pages for the heap and
// 64 MB of freed memory kept for reuse; the re-run puts GLIBC_TUNABLES back as it was, so that
// the processes it starts see the caller's environment. Where the exec fails, only the kept
// memory is set, by mallopt. Elsewhere it does nothing.
void tune_allocator(char** argv);

// What tune_allocator left in force, for the run record: "huge pages, 64 MB kept (re-run)",
// "64 MB kept (mallopt)", "the caller's GLIBC_TUNABLES", "default (HULLMESH_DEFAULT_ALLOCATOR)"
// or "default".
const char* allocator_setting();

}  // namespace hm::cli
