#pragma once
// One float buffer per thread, reused by the tasks a worker thread runs one
// after another (BAKE_TILE's tile rows, TRANSFORM_COLUMNS' column images).
// A fresh zero-filled buffer per task — 100 MB for a 32² tile at N = 64,
// 400 MB at N = 128 — cost a memset and a page fault per 4 KiB page: the
// N = 64 tile's transpose took 75 ms into a fresh block against 31 ms into a
// reused one (a stand-alone timing). The thread keeps the largest buffer
// asked for (one per thread, not one per phase) until ReleaseTaskBuffer.
//
// Even once per thread, those faults cost: ~15 µs each on this project's
// VMs, so ~0.4 s for each thread's first tile at N = 64 (25 600 faults) and
// ~1.5 s at N = 128. The buffer asks for transparent huge pages (madvise;
// the kernel may decline, and then it is as before), one fault per 2 MiB:
// the refined bunny bake (hilbert 64², N = 64, bench_bake_phases) took
// 127 000 faults before and 49 000 after.
#include <cstddef>
#include <span>

namespace wavebake {

// `floats` floats of this thread's buffer. Their contents are unspecified
// (what the last task left): the caller writes every element it reads. One
// span per thread at a time: the next call may move the buffer.
std::span<float> TaskBuffer(size_t floats);

// Frees this thread's buffer (a worker thread with no task to run).
void ReleaseTaskBuffer();

}  // namespace wavebake
