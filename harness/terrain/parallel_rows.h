#pragma once
// Row-band parallelism for the per-sample terrain passes (normal map, density map, plane fit,
// procedural generation). Each band writes only its own rows and reads shared inputs, so the
// result is bit-identical whatever the thread count: threads change the time, never the output.
#include <functional>

namespace lb {

// Threads the terrain passes use: LODBENCH_THREADS when set to a positive integer (the load
// benchmark's --threads sets it, to emulate a smaller machine), else hardware_concurrency (>= 1).
int terrainThreads();

// Runs body(r0, r1) over contiguous bands [r0, r1) that cover [0, rows) exactly once, on up to
// terrainThreads() threads (the calling thread takes the first band). Bands are at least
// minRowsPerBand rows so that small terrains (the tests') stay on one thread.
void parallelRows(int rows, const std::function<void(int r0, int r1)>& body, int minRowsPerBand = 64);

}  // namespace lb
