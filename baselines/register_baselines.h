// Registers the baseline contact models with the model factory
// (experiment/model_factory.h), so scenes and experiments can make them by name.
#pragma once

namespace contactlab {

// Registers "fcl", "bullet", "reference" (only with CGAL) and, when baselines/vps is built,
// "vps" and "vps-repulsion". Each takes k_C and L from the scene's model section; FCL and
// Bullet read A's and B's meshes, the reference also needs B's mesh closed. Idempotent.
void RegisterBaselineContactModels();

}  // namespace contactlab
