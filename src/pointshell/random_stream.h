// Counter-based random streams for reproducible parallel sampling (Barbič & James 2008,
// sec. 2.4: random initial positions for particle repulsion). Every point draws from its own
// stream seeded from (seed, index), so results do not depend on the number of threads.
#pragma once

#include <cstdint>

namespace contactlab {

// SplitMix64 finaliser: a bijective 64-bit mix.
inline std::uint64_t MixBits(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// A SplitMix64 generator; RandomStream(seed, index) is the stream of item INDEX.
class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t index)
      : state_(MixBits(seed ^ MixBits(index * 0xd1b54a32d192ed03ull + 0x632be59bd9b4e019ull))) {}

  std::uint64_t Next() {
    state_ += 0x9e3779b97f4a7c15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  // Uniform in [0, 1), 53 random bits.
  double Uniform() { return double(Next() >> 11) * 0x1.0p-53; }

 private:
  std::uint64_t state_;
};

}  // namespace contactlab
