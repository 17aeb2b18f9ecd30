// Counts heap allocations in a test program (link tests/allocation_counter.cc into it), to
// check that hot loops allocate nothing: malloc, calloc, realloc, the aligned allocators and
// operator new are all counted, whichever thread calls them.
#pragma once

namespace contactlab::testing {

// Allocations so far in this process.
long AllocationCount();

}  // namespace contactlab::testing
