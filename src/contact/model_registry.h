// Contact models made by name (docs/architecture.md, "The contact interface"), so a scene or an
// experiment config can list several and compare them. Every model, the paper's included,
// registers from its own folder through contactlab_contact_model() in its CMakeLists
// (docs/architecture.md, "Adding a model"). An entry is the model's whole face to the rest: its
// name, what it needs from the two bodies (so callers build only that and never guess from a
// model's name), its own keys under the scene's `model:` section and its blocks under
// `bodies[]`, each a parameter table; contact/ names no model and no model's keys.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_model.h"
#include "contact/contact_params.h"
#include "util/param_values.h"

namespace contactlab {

struct TriangleMesh;
class DistanceField;
struct Pointshell;
class DeformablePointshell;
class DeformedDistanceField;

// One body's data, built on demand (and cached) by the caller: scene/ implements it for
// scene bodies. Each accessor throws Error naming the body when the data cannot be built.
class ContactBody {
 public:
  virtual ~ContactBody() = default;
  virtual std::string_view body_name() const = 0;
  virtual std::shared_ptr<const TriangleMesh> mesh() = 0;            // body frame, metres
  virtual std::shared_ptr<const DistanceField> field() = 0;          // body frame
  virtual std::shared_ptr<const Pointshell> pointshell() = 0;        // body frame
  virtual std::uint64_t sampling_seed() const = 0;                   // seed of the body's point sampling
  // A deformable body (paper sec. 4) carries a reduced model; rigid bodies answer false.
  virtual bool deformable() const { return false; }
  // The pointshell embedded in the body's reduced model, body frame.
  virtual std::shared_ptr<const DeformablePointshell> deformable_pointshell() { return nullptr; }
  // The deformed distance field of a deformable body in the field role (paper sec. 4.2).
  virtual std::shared_ptr<const DeformedDistanceField> deformed_field() { return nullptr; }
  // Its blocks of the models' per-body parameters (ContactModelEntry::body_blocks: a pressure
  // modulus, a sphere packing), each read by its model as values.Get(ITS_TABLE).
  virtual const ParamValues& model_blocks() const {
    static const ParamValues defaults;
    return defaults;
  }
  // Where a model may keep data it derives from the body's field (an inner-sphere packing): a
  // file unique to the field's cache key and KEY (the model's kind, parameters and builder
  // version, as text), or empty when the caller keeps no cache. The model reads the file when
  // it is there and good, and otherwise writes it (atomically).
  virtual std::filesystem::path DerivedCachePath(std::string_view key) {
    (void)key;
    return {};
  }
};

// What a model reads of the two bodies (A: pointshell role, B: field role).
struct ContactModelNeeds {
  bool pointshell_A = false;  // A's pointshell
  bool field_A = false;       // A's distance field (e.g. to sample another pointshell)
  bool field_B = false;       // B's distance field
  bool mesh_A = false;        // A's triangle mesh
  bool mesh_B = false;        // B's triangle mesh
  bool closed_mesh_B = false; // B's mesh must be closed (an inside test)
  // Its penetration depth is measured on B's field grid, so reports may give it in voxels
  // of B's field (experiment column depth_voxels).
  bool depth_in_field_voxels = false;
  // It renders A's deformation (A's deformable pointshell when A is deformable). Models
  // without it refuse a deformable A rather than treat it as rigid.
  bool deformable_A = false;
  // It renders B's deformation through B's deformed distance field (paper sec. 4.2). Models
  // without it refuse a deformable B.
  bool deformable_B = false;
};

// What a factory is given: the two bodies and the scene's model section.
struct ContactModelInputs {
  ContactBody& A;
  ContactBody& B;
  const ContactParams& params;      // the keys every model shares
  const ParamValues& model_params;  // each model's own keys (ContactModelEntry::pair_params)

  // The model's own keys, read by the table its entry carries (defaults when the scene gave none).
  template <class Spec>
  const Spec& Params(const ParamTable<Spec>& table) const {
    return model_params.Get(table);
  }
};

// A model's block of parameters as the registry carries it: TABLE's rows over a ParamValues
// (util/param_values.h), so scenes read, check, sweep and document it without knowing its
// struct. KEY is where a per-body block sits under bodies[] ("pressure_field"; "" for a pair
// block, whose keys sit in `model:` itself), DOC its meaning there.
struct ModelParamBlock {
  std::string key;
  std::string doc;
  std::shared_ptr<const ParamTable<ParamValues>> table;
};
template <class Spec>
ModelParamBlock ParamBlock(const ParamTable<Spec>& table, std::string key = {}, std::string doc = {}) {
  return {std::move(key), std::move(doc), std::make_shared<const ParamTable<ParamValues>>(ErasedTable(table))};
}

using ContactModelFactory = std::function<std::unique_ptr<ContactModel>(const ContactModelInputs&)>;

struct ContactModelEntry {
  std::string name;         // what scenes and configs write: "pointshell", "fcl", ...
  std::string description;  // one line for listings
  ContactModelNeeds needs;
  ContactModelFactory make;
  // A reference for comparisons (an experiment's `reference:`), not a model to compare: made by
  // name like any other, but left out of ContactModelNames().
  bool reference_only = false;
  // Its contact is a surface it keeps for display (ContactModel::KeepContactSurface): the viewer
  // draws it, and makes no other model to ask.
  bool contact_surface = false;
  // Its Evaluate may allocate after its first call (a library's own containers: Bullet's
  // triangle-pair list, CGAL's traversals), so the haptic cycle's promise of no allocation does
  // not hold with it; `contactlab models` says so, and the allocation tests leave it out.
  bool allocates = false;
  // Its contacts come from the two meshes (a mesh-pair library), not from a distance field's
  // voxels: they begin within the library's own margin of the surfaces, not within a voxel.
  bool mesh_pair_contacts = false;
  // Which bodies it carries friction between (ContactParams::friction, contact/friction.h): a
  // scene that asks for friction is refused by a model with kNone, and by one with
  // kRigidBodies when a body deforms.
  FrictionSupport friction = FrictionSupport::kNone;
  // Its own keys under the scene's `model:` section (ParamBlock(ITS_TABLE)); none when it has
  // none. Entries of one folder may carry the same table: its keys are read once.
  std::optional<ModelParamBlock> pair_params;
  // Its blocks under each of the scene's bodies (ParamBlock(ITS_TABLE, "key", "meaning")).
  std::vector<ModelParamBlock> body_blocks;
  // The harness's depth probe, when this entry provides it (scene/contact_placement.h
  // TouchAlong: bodies placed at a penetration depth): a model made from the same inputs whose
  // stats.max_penetration is the deepest penetration of A into B over all of A's points at every
  // query, with no culling, no budget and no coherence. Null for every entry but the one that
  // declares it (the paper's tree-less model at its deepest level).
  ContactModelFactory make_depth_probe;
  // The stiffness every model is put at under `model.stiffness: matched`
  // (scene/stiffness_match.h): true on the one entry whose force at the reference press the
  // others are scaled to (the paper's model).
  bool stiffness_reference = false;
  // Its own keys (in OWN, every model's) set for its most detailed evaluation, what it is run at
  // as an experiment's reference (the paper's model: its deepest level). Null: as the scene says.
  std::function<void(ParamValues& own)> at_full_detail;
  // What the model refuses of the scene's parameters given which bodies deform, checked before
  // any body data is built: throws Error naming WHERE. Null: nothing beyond `needs`.
  std::function<void(const ContactParams& params, const ParamValues& model_params, bool deformable_A,
                     bool deformable_B, std::string_view where)>
      check;
};

// Adds (or replaces) the entry of ENTRY.name.
void RegisterContactModel(ContactModelEntry entry);

// The entry registered as NAME, or null.
const ContactModelEntry* FindContactModel(std::string_view name);

// The one registered entry for which HAS holds: a trait exactly one entry declares (the depth
// probe, the stiffness reference). Throws Error("WHERE: ...") naming TRAIT when none or several
// entries declare it.
const ContactModelEntry& SoleContactModelWith(const std::function<bool(const ContactModelEntry&)>& has,
                                              std::string_view trait, std::string_view where);

// Checks that model NAME can render bodies BODY_A and BODY_B (names, for messages) that deform
// as DEFORMABLE_A and DEFORMABLE_B with PARAMS, without building anything: throws
// Error("WHERE: unknown contact model 'x' (known: ...)") when NAME is unknown, Error when a body
// deforms and the model does not render it, Error when PARAMS ask for friction the model does
// not carry for these bodies, and the entry's check's errors.
void CheckContactModel(std::string_view name, const ContactParams& params, const ParamValues& model_params,
                       std::string_view body_A, bool deformable_A, std::string_view body_B, bool deformable_B,
                       std::string_view where);
// Makes model NAME from INPUTS, after CheckContactModel; the factory's errors otherwise.
std::unique_ptr<ContactModel> MakeContactModel(std::string_view name, const ContactModelInputs& inputs,
                                               std::string_view where);

// Counts the registrations so far: a table built from the entries (a scene's model section, its
// body blocks) is rebuilt when it changed.
std::uint64_t ContactModelRegistryVersion();

// Every registered entry, sorted by name (references included).
std::vector<const ContactModelEntry*> ContactModelEntries();

// Every registered name but the references-only ones, sorted.
std::vector<std::string> ContactModelNames();
// The references-only names (ContactModelEntry::reference_only), sorted.
std::vector<std::string> ReferenceModelNames();

}  // namespace contactlab
