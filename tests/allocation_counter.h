// Counts heap allocations made through operator new in a test program (link
// tests/allocation_counter.cc into it), to check that hot loops allocate nothing.
#pragma once

namespace contactlab::testing {

// Allocations so far in this process.
long AllocationCount();

}  // namespace contactlab::testing
