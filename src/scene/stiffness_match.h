// Like with like: the scene key `model.stiffness: matched` puts every contact model at the
// paper's model's stiffness before models are compared or a loop is closed with them (the
// pressure field's default modulus pushes back about 100x more softly than the penalty models,
// and a softer model looks more stable in a closed loop for that reason alone).
//
// The rule: a reference press of the scene, body A moved from its start pose toward B's origin
// to where its mesh first touches B's surface (a vertex of A's mesh on B's zero level set, not
// the paper's model's first force, which comes earlier by its pointshell's offset) and then
// match_depth further. There (bodies at rest, coherence reset) the paper's model (`pointshell`,
// the scene's parameters) gives the force F and the model f; the model's wrench is scaled by
// s = F . f / |f|^2, the factor that brings s f closest to F (equal when they are parallel)
// (ScaledContactModel, contact/scaled_contact_model.h): the same as multiplying its own
// stiffness keys by s, since every model's wrench is linear in them. One depth, not a fit over
// several: the models' laws differ in shape (the pressure field's force grows with the square of
// the depth on a ball, the paper's linearly after an offset), so they agree at one press only.
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "contact/contact_model.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"

namespace contactlab {

// The factor s above for MODEL (named NAME) in SCENE. Throws Error naming the scene file when
// the bodies never touch along the press, or when the model gives no force (or one opposite to
// the paper's) on it.
double MatchedStiffnessScale(ContactModel& model, std::string_view name, const Scene& scene, SceneAssets& assets);

// MODEL as SCENE's `model.stiffness` says: itself under `own` and for the paper's model, else
// wrapped in a ScaledContactModel with MatchedStiffnessScale.
std::unique_ptr<ContactModel> ApplyStiffnessRule(std::unique_ptr<ContactModel> model, std::string_view name,
                                                 const Scene& scene, SceneAssets& assets);

}  // namespace contactlab
