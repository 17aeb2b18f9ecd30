// The machine's roofline beside the contact benchmarks: memory latency and bandwidth per cache
// level, and the cost of one trilinear field lookup from cache and from memory.
#pragma once

namespace contactlab::bench {

// Registers roofline/latency, roofline/read, roofline/triad (working sets sized from the
// caches of cpu0) and roofline/lookup (dense 128^3 and 256^3 fields, random in the box or in an 8-cell cube).
void RegisterRooflineBenchmarks();

}  // namespace contactlab::bench
