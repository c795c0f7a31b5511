#pragma once
// How the process's heap treats large blocks.

namespace petroscope {

/// Keeps freed blocks of up to 32 MB (glibc's largest threshold) in the heap, untrimmed below 1 GB, instead
/// of returning them to the system at once (mmap). Images and spectra of a few to tens of MB are allocated
/// and freed in turn; reused, their pages need no new first-touch faults, which cost about a third of a 512²
/// figure's time on a 2-core VM. A no-op outside glibc.
void keep_large_blocks_in_heap();

}  // namespace petroscope
