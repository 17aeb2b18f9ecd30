// contactlab.Model: a registered contact model (contact/model_registry.h) between a scene's
// bodies, queried at poses given as NumPy arrays, one at a time or in batches (the GIL released
// for the batch). contactlab.models(): the registered names.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bindings.h"
#include "contact/contact_stats_fields.h"
#include "contact/model_registry.h"
#include "scene/reduced_coordinates.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "scene/scene_query.h"
#include "poses.h"
#include "scene_handle.h"
#include "util/config_node.h"
#include "util/error.h"

namespace py = pybind11;

namespace contactlab::python {
namespace {

// A model and what it evaluates with. Calls hold MUTEX (ModelLock), taken after releasing the
// GIL, so a model written in Python (which takes the GIL in Evaluate) cannot deadlock against
// another thread; OWNER, the thread holding it, lets a call from inside the model's own
// evaluation fail instead of waiting for itself.
struct ModelHandle {
  std::shared_ptr<SceneHandle> scene_handle;  // keeps the bodies' data alive
  Scene scene;                                // the scene with the keyword overrides applied
  std::string name;
  std::unique_ptr<ContactModel> model;
  std::mutex mutex;
  std::atomic<std::thread::id> owner{};  // the thread holding MUTEX; none when free
  std::int64_t cycle = 0;                // the next query's cycle when queries are not reset
  // Whether KeepContacts was asked of the model (query(contacts=True)) and what it answered.
  bool contacts_asked = false;
  bool has_contacts = false;
};

// Room for the contacts of one query(contacts=True) (more are counted in not_kept).
constexpr int kMaxContacts = 1 << 20;

// Holds H's mutex for one call (CALL: its Python name) with the GIL released, the GIL taken
// back after the mutex is let go. Throws Error naming the model when this thread already holds
// it: a Python model's function calling its own Model (query, query_many, reset) would
// otherwise wait for itself forever. Construct with the GIL held.
class ModelLock {
 public:
  ModelLock(ModelHandle& h, const char* call) : h_(h) {
    if (h.owner.load() == std::this_thread::get_id()) {
      Fail(h.name, std::string(call) + "() called from inside this model's own evaluation (its Python "
                   "function calling its own Model); a model cannot query itself");
    }
    release_.emplace();
    lock_ = std::unique_lock<std::mutex>(h.mutex);
    h.owner.store(std::this_thread::get_id());
  }
  ~ModelLock() {
    h_.owner.store(std::thread::id());
    lock_.unlock();
    release_.reset();
  }
  ModelLock(const ModelLock&) = delete;
  ModelLock& operator=(const ModelLock&) = delete;

 private:
  ModelHandle& h_;
  std::optional<py::gil_scoped_release> release_;
  std::unique_lock<std::mutex> lock_;
};

// Evaluates one query at X_WA, X_WB: from a fresh state (Reset, cycle 0: what the command's
// `contact` does) when RESET, else as the next haptic cycle. Called under a ModelLock of H.
// The one check of every model's result on both paths (query, query_many): a non-finite wrench
// or K_B is an error, never a result, as the command's `contact` refuses it; Error names the
// model, and ROW (>= 0) the query of a batch.
ContactResult EvaluateLocked(ModelHandle& h, const Pose& X_WA, const Pose& X_WB, bool reset,
                             const BodyDeformation* deformation_A, const BodyDeformation* deformation_B,
                             py::ssize_t row = -1) {
  ContactQuery q = SceneContactQuery(h.scene, X_WA, X_WB);
  q.deformation_A = deformation_A;
  q.deformation_B = deformation_B;
  if (reset) {
    h.model->Reset();
    h.cycle = 0;
  }
  q.cycle = h.cycle++;
  ContactResult r = h.model->Evaluate(q);
  if (!r.on_B.force.allFinite() || !r.on_B.torque.allFinite() || !r.K_B.allFinite()) {
    Fail((row < 0 ? "" : "query_many[" + std::to_string(row) + "]: ") + h.name,
         "gave a non-finite wrench or stiffness at these poses and coordinates");
  }
  return r;
}

// Every ContactStats field (contact/contact_stats_fields.h): counts as int, the rest as float.
py::dict StatsDict(const ContactStats& s) {
  py::dict d;
  for (const ContactStatField& f : kContactStatFields) {
    if (f.count) {
      d[f.name] = std::int64_t(f.value(s));
    } else {
      d[f.name] = f.value(s);
    }
  }
  return d;
}

py::array_t<double> Vector(const double* v, py::ssize_t n) {
  py::array_t<double> a(n);
  std::copy(v, v + n, a.mutable_data());
  return a;
}

py::array_t<double> Matrix6(const Matrix6d& K) {
  py::array_t<double> a({6, 6});
  Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(a.mutable_data()) = K;
  return a;
}

// Reduced coordinates VALUES for BODY, checked as the command's --q-a / --q-b are (their count,
// finite values, a finite deformation U q): ArgumentError naming WHERE when any check fails,
// TypeError when VALUES are not real numbers (DoublesFromObject).
ReducedState ReducedFrom(py::handle values, BodyAssets& body, const std::string& where) {
  const DoubleArray q = DoublesFromObject(values, where);
  if (q.ndim() != 1) FailArgument(where, "reduced coordinates are a 1-D array (r,)");
  for (py::ssize_t i = 0; i < q.shape(0); ++i) {
    if (!std::isfinite(q.data()[i])) FailArgument(where, "value " + std::to_string(i + 1) + " is not a finite number");
  }
  std::ostringstream text;
  text.precision(17);
  for (py::ssize_t i = 0; i < q.shape(0); ++i) text << (i ? "," : "") << q.data()[i];
  // The command's check of --q-a (count, a deformation that fits) is of this argument.
  try {
    return ParseReducedCoordinates(text.str(), body, where);
  } catch (const ArgumentError&) {
    throw;
  } catch (const Error& e) {
    throw ArgumentError(e.what());
  }
}

// The contacts LIST as a dict of NumPy arrays: points, normals (N, 3), depths (N,), areas and
// pressures (N,) when the model has them, tangential (N, 3) and sticking (N,) with friction on,
// not_kept (int).
py::dict ContactsDict(const ContactList& list) {
  const py::ssize_t n = list.size();
  auto rows = [n](const std::vector<Eigen::Vector3d>& v) {
    py::array_t<double> a({n, py::ssize_t(3)});
    for (py::ssize_t i = 0; i < n; ++i) {
      const double* row = v[std::size_t(i)].data();
      std::copy(row, row + 3, a.mutable_data() + 3 * i);
    }
    return a;
  };
  py::dict d;
  d["points"] = rows(list.points);
  d["normals"] = rows(list.normals);
  d["depths"] = Vector(list.depths.data(), n);
  if (!list.areas.empty()) {
    d["areas"] = Vector(list.areas.data(), n);
    d["pressures"] = Vector(list.pressures.data(), n);
  }
  if (!list.tangential.empty()) {
    d["tangential"] = rows(list.tangential);
    py::array_t<bool> sticking(n);
    for (py::ssize_t i = 0; i < n; ++i) sticking.mutable_data()[i] = list.sticking[std::size_t(i)] != 0;
    d["sticking"] = sticking;
  }
  d["not_kept"] = list.not_kept;
  return d;
}

py::dict Query(ModelHandle& h, py::handle X_WA, py::handle X_WB, bool reset, py::handle q_A, py::handle q_B,
               bool contacts) {
  const Pose pose_A = PoseFromArray(DoublesFromObject(X_WA, "X_WA"), "X_WA");
  const Pose pose_B = PoseFromArray(DoublesFromObject(X_WB, "X_WB"), "X_WB");
  SceneAssets& assets = h.scene_handle->assets;
  std::unique_ptr<ReducedState> state_A, state_B;
  if (!q_A.is_none()) state_A = std::make_unique<ReducedState>(ReducedFrom(q_A, assets.A, "q_A"));
  if (!q_B.is_none()) state_B = std::make_unique<ReducedState>(ReducedFrom(q_B, assets.B, "q_B"));
  ReducedVector force_A, force_B;
  const BodyDeformation deformation_A{state_A.get(), &force_A}, deformation_B{state_B.get(), &force_B};
  const bool deform_A = assets.A.deformable(), deform_B = assets.B.deformable();
  ContactResult r;
  ContactList list;
  bool listed = false;
  {
    const ModelLock lock(h, "query");
    // Contacts asked for the first time: the model reserves room and records from now on.
    if (contacts && !h.contacts_asked) {
      h.has_contacts = h.model->KeepContacts(kMaxContacts);
      h.contacts_asked = true;
    }
    r = EvaluateLocked(h, pose_A, pose_B, reset, deform_A ? &deformation_A : nullptr,
                       deform_B ? &deformation_B : nullptr);
    if (contacts && h.has_contacts) {
      h.model->LatestContacts(&list);
      listed = true;
    }
  }
  // As the command: a refused query is an error, never a result (a non-finite one raised above).
  if (r.stats.faults > 0) Fail(h.name, "refused the query (a deformation that does not fit its body); no wrench");
  py::dict d;
  d["model"] = h.name;
  d["force"] = Vector(r.on_B.force.data(), 3);
  d["torque"] = Vector(r.on_B.torque.data(), 3);
  const Vector6d w = r.on_B.AsVector();
  d["wrench"] = Vector(w.data(), 6);
  d["K_B"] = Matrix6(r.K_B);
  d["stats"] = StatsDict(r.stats);
  if (deform_A) d["reduced_force_A"] = Vector(force_A.data(), force_A.size());
  if (deform_B) d["reduced_force_B"] = Vector(force_B.data(), force_B.size());
  d["contacts"] = listed ? py::object(ContactsDict(list)) : py::object(py::none());
  return d;
}

// The number of queries of a batch of NA poses of A and NB of B, broadcast as NumPy does: a
// single pose is used for every query of the other side (so one against none is none), else
// the counts must agree. Throws ArgumentError naming both counts.
std::size_t BatchSize(std::size_t na, std::size_t nb) {
  if (na == 1) return nb;
  if (nb == 1 || nb == na) return na;
  FailArgument("query_many", "poses_A has " + std::to_string(na) + " poses and poses_B " + std::to_string(nb) +
                                 "; give as many of each, or one pose for either");
}

py::dict QueryMany(ModelHandle& h, py::handle poses_A, py::handle poses_B, bool reset) {
  const std::vector<Pose> A = PosesFromArray(DoublesFromObject(poses_A, "poses_A"), "poses_A");
  const std::vector<Pose> B = PosesFromArray(DoublesFromObject(poses_B, "poses_B"), "poses_B");
  const py::ssize_t n = py::ssize_t(BatchSize(A.size(), B.size()));
  py::array_t<double> wrench({n, py::ssize_t(6)});
  py::array_t<double> K({n, py::ssize_t(6), py::ssize_t(6)});
  double* w = wrench.mutable_data();
  double* k = K.mutable_data();
  constexpr std::size_t kFields = kContactStatFields.size();
  std::vector<double> values(std::size_t(n) * kFields);  // per query, every stats field
  // Deformable bodies are queried at rest, as the command's `contact` without --q-a / --q-b.
  SceneAssets& assets = h.scene_handle->assets;
  ReducedVector force_A, force_B;
  const BodyDeformation deformation_A{nullptr, &force_A}, deformation_B{nullptr, &force_B};
  const BodyDeformation* dA = assets.A.deformable() ? &deformation_A : nullptr;
  const BodyDeformation* dB = assets.B.deformable() ? &deformation_B : nullptr;
  {
    const ModelLock lock(h, "query_many");
    for (py::ssize_t i = 0; i < n; ++i) {
      const ContactResult r = EvaluateLocked(h, A[A.size() == 1 ? 0 : i], B[B.size() == 1 ? 0 : i], reset, dA, dB, i);
      Eigen::Map<Vector6d>(w + 6 * i) = r.on_B.AsVector();
      Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(k + 36 * i) = r.K_B;
      for (std::size_t f = 0; f < kFields; ++f) values[std::size_t(i) * kFields + f] = kContactStatFields[f].value(r.stats);
    }
  }
  // One array per field: int64 for the counts, float64 for the rest.
  py::dict stats;
  for (std::size_t f = 0; f < kFields; ++f) {
    if (kContactStatFields[f].count) {
      py::array_t<std::int64_t> a(n);
      for (py::ssize_t i = 0; i < n; ++i) a.mutable_data()[i] = std::int64_t(values[std::size_t(i) * kFields + f]);
      stats[kContactStatFields[f].name] = a;
    } else {
      py::array_t<double> a(n);
      for (py::ssize_t i = 0; i < n; ++i) a.mutable_data()[i] = values[std::size_t(i) * kFields + f];
      stats[kContactStatFields[f].name] = a;
    }
  }
  py::dict d;
  d["model"] = h.name;
  d["wrench"] = wrench;
  d["force"] = wrench[py::make_tuple(py::ellipsis(), py::slice(0, 3, 1))];
  d["torque"] = wrench[py::make_tuple(py::ellipsis(), py::slice(3, 6, 1))];
  d["K_B"] = K;
  d["stats"] = stats;
  return d;
}

}  // namespace

py::object MakeModel(const std::shared_ptr<SceneHandle>& scene, const std::string& name, const py::kwargs& params) {
  auto h = std::make_shared<ModelHandle>();
  h->scene_handle = scene;
  h->scene = scene->scene;
  h->name = name.empty() ? scene->scene.models.front() : name;
  if (params.size() > 0) {
    // The keyword arguments as a model section (JSON is YAML), read by the scene's own table.
    py::dict section;
    section["model"] = params;
    const std::string text = py::module_::import("json").attr("dumps")(section).cast<std::string>();
    h->scene = WithModelSection(h->scene, ConfigNode::LoadString(text, "Scene.model() keyword arguments").Get("model"));
  }
  h->model = MakeSceneContactModel(h->name, h->scene, scene->assets);
  return py::cast(h);
}

void BindModel(py::module_& m) {
  py::class_<ModelHandle, std::shared_ptr<ModelHandle>>(
      m, "Model",
      "A contact model between a scene's bodies (Scene.model). Results are the wrench on body B about its "
      "origin, world frame, SI units, and K_B = d(wrench on B)/d(pose of B), ordered (dx, dtheta).")
      .def_property_readonly("name", [](const ModelHandle& h) { return h.name; })
      .def_property_readonly("node_budget", [](const ModelHandle& h) { return h.scene.node_budget; })
      .def("query", &Query, py::arg("X_WA"), py::arg("X_WB"), py::kw_only(), py::arg("reset") = true,
           py::arg("q_A") = py::none(), py::arg("q_B") = py::none(), py::arg("contacts") = false,
           "One contact query at the world poses X_WA, X_WB of bodies A and B, each a (7,) array (x, y, z, "
           "qw, qx, qy, qz; metres) or a (4, 4) matrix. RESET (default): from a fresh state, as `contactlab "
           "contact` evaluates; False: as the next haptic cycle (temporal coherence). Q_A / Q_B: reduced "
           "coordinates (r,) of a deformable body (default: at rest). Returns a dict: force (3,), torque "
           "(3,), wrench (6,), K_B (6, 6), stats (dict of the ContactStats fields), reduced_force_A / "
           "_B for deformable bodies, and contacts: None unless CONTACTS is True and the model has a contact "
           "list, else a dict of the query's contacts, world frame: points (N, 3) float64 metres, normals "
           "(N, 3) unit (direction of the force on B), depths (N,) metres, areas (N,) m^2 and pressures (N,) "
           "Pa for a surface model (pressure-field), tangential (N, 3) newtons (each contact's friction "
           "force on B) and sticking (N,) bool with the scene's friction on, not_kept (int: contacts past "
           "the room kept, 2^20). "
           "Raises contactlab.ArgumentError (a ValueError) naming the argument when a "
           "pose or Q has the wrong shape or a value that is not finite, TypeError when it is not real "
           "numbers (complex, strings, None); contactlab.Error when the model refuses the query or gives a "
           "non-finite wrench or K_B, or when called from inside this model's own evaluation (a Python "
           "model's function querying its own Model).")
      .def("query_many", &QueryMany, py::arg("poses_A"), py::arg("poses_B"), py::kw_only(), py::arg("reset") = true,
           "N queries: POSES_A and POSES_B are (N, 7) or (N, 4, 4) arrays (either may be one pose, used for "
           "every query, as NumPy broadcasts; one pose against an empty batch is an empty batch). The GIL is "
           "released while they run. Returns a dict: wrench (N, 6), force and torque (N, 3) views of it, "
           "K_B (N, 6, 6), stats (dict of (N,) arrays; faults counts refused queries, which give zero). "
           "Each row equals query() at the same poses. Bad poses raise as query() does, naming poses_A[i] or "
           "poses_B[i]. Raises contactlab.Error naming the row (query_many[i]) "
           "when a model gives a non-finite wrench or K_B, as query() does. An empty batch (N = 0) is no "
           "error: every array has its shape with N = 0.")
      .def("reset", [](ModelHandle& h) {
        const ModelLock lock(h, "reset");
        h.model->Reset();
        h.cycle = 0;
      }, "Forgets temporal state (coherence, level-of-detail hysteresis).")
      .def("__repr__", [](const ModelHandle& h) { return "<contactlab.Model " + h.name + " on " + h.scene.name + ">"; });

  m.def(
      "models",
      [](bool references) {
        std::vector<std::string> names = ContactModelNames();
        if (references) {
          for (const std::string& n : ReferenceModelNames()) names.push_back(n);
        }
        return names;
      },
      py::arg("references") = false,
      "The registered contact model names, sorted (with REFERENCES: the reference-only ones after them).");
  m.def(
      "model_description",
      [](const std::string& name) {
        const ContactModelEntry* e = FindContactModel(name);
        if (e == nullptr) Fail("model_description", "unknown contact model '" + name + "'");
        return e->description;
      },
      py::arg("name"), "The one-line description of registered model NAME.");
}

}  // namespace contactlab::python
