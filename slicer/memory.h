// Returning freed heap memory to the operating system between the phases of a large job.
#pragma once

namespace strand::slicer {

// glibc keeps freed small blocks mapped, so a phase's released data (toolpath layers already
// planned, stroke copies already ordered) would still count in the peak memory next to the
// large program that follows; this hands those pages back. A no-op elsewhere.
void release_free_memory();

}  // namespace strand::slicer
