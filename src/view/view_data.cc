#include "view/view_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <tuple>

#ifdef CONTACTLAB_HAVE_CGAL
#include "baselines/reference/simplify_mesh.h"
#endif
#include "contact/model_registry.h"
#include "deform/embedded_points.h"
#include "experiment/csv_line.h"
#include "experiment/experiment_config.h"
#include "experiment/studies/contact/result_csv.h"
#include "experiment/study.h"
#include "util/atomic_file.h"
#include "util/config_node.h"
#include "util/error.h"
#include "util/parse_number.h"
#include "view/display_points.h"
#include "view/field_slice.h"
#include "view/page_encoding.h"
#include "scene/scene_query.h"

namespace contactlab {
namespace {

namespace fs = std::filesystem;

nlohmann::json PoseJson(const Pose& X) {
  return {X.translation.x(), X.translation.y(), X.translation.z(),
          X.rotation.w(),    X.rotation.x(),    X.rotation.y(),    X.rotation.z()};
}

// The mesh the page draws: BODY's, thinned by edge collapse to MAX_TRIANGLES when it has more
// (builds with CGAL; others draw it whole).
TriangleMesh DisplayMesh(BodyAssets& body, int max_triangles) {
#ifdef CONTACTLAB_HAVE_CGAL
  if (max_triangles > 0 && body.mesh()->num_triangles() > max_triangles) {
    return SimplifyMesh(*body.mesh(), max_triangles, "view: mesh of body " + body.spec().name);
  }
#else
  (void)max_triangles;
#endif
  return *body.mesh();
}

nlohmann::json BodyJson(BodyAssets& body, const Pose& X_WBody, const TriangleMesh& mesh) {
  std::vector<float> positions;
  positions.reserve(mesh.vertices.size() * 3);
  for (const Eigen::Vector3d& p : mesh.vertices) positions.insert(positions.end(), {float(p.x()), float(p.y()), float(p.z())});
  std::vector<std::uint32_t> indices;
  indices.reserve(mesh.triangles.size() * 3);
  for (const Eigen::Vector3i& t : mesh.triangles) {
    indices.insert(indices.end(), {std::uint32_t(t.x()), std::uint32_t(t.y()), std::uint32_t(t.z())});
  }
  return {{"name", body.spec().name},
          {"role", body.spec().role},
          {"deformable", body.deformable()},
          {"pose", PoseJson(X_WBody)},
          {"vertices", mesh.num_vertices()},
          {"triangles", mesh.num_triangles()},
          {"source_triangles", body.mesh()->num_triangles()},
          {"positions", EncodeArray(positions)},
          {"indices", EncodeArray(indices)}};
}

nlohmann::json Vector3Json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

// SceneViewData, and the meshes drawn (A's, B's) in *MESHES.
nlohmann::json SceneViewDataAndMeshes(const Scene& scene, SceneAssets& assets, const SceneViewOptions& options,
                                      const std::optional<BodyPoses>& poses, std::array<TriangleMesh, 2>* meshes) {
  const Pose X_WA = poses ? poses->X_WA : scene.pointshell_body.pose;
  const Pose X_WB = poses ? poses->X_WB : scene.field_body.pose;
  nlohmann::json j;
  j["title"] = scene.name;
  j["scene"] = scene.file;
  *meshes = {DisplayMesh(assets.A, options.max_triangles), DisplayMesh(assets.B, options.max_triangles)};
  j["bodies"] = {BodyJson(assets.A, X_WA, (*meshes)[0]), BodyJson(assets.B, X_WB, (*meshes)[1])};

  // A's pointshell, thinned per level.
  const auto shell = assets.A.pointshell();
  const DisplayPoints points = DecimatePointshell(*shell, options.max_points);

  // Points in contact at these poses (sec. 2.1: d < 0 in B's field): of all, and which drawn.
  const auto field = assets.B.field();
  const Pose X_BA = X_WB.Inverse() * X_WA;
  int in_contact = 0;
  for (int i = 0; i < shell->num_points(); ++i) {
    if (field->Distance(X_BA * Eigen::Vector3d(shell->x[i], shell->y[i], shell->z[i])) < 0) ++in_contact;
  }
  std::vector<std::uint8_t> contact(points.num_kept());
  for (int i = 0; i < points.num_kept(); ++i) {
    const Eigen::Vector3d p_A(points.xyz[3 * i], points.xyz[3 * i + 1], points.xyz[3 * i + 2]);
    contact[i] = field->Distance(X_BA * p_A) < 0 ? 1 : 0;
  }
  j["pointshell"] = {{"body", 0},
                     {"points", shell->num_points()},
                     {"levels", shell->num_levels()},
                     {"kept", points.kept},
                     {"total", points.total},
                     {"in_contact", in_contact},
                     {"positions", EncodeArray(points.xyz)},
                     {"level", EncodeArray(points.level)},
                     {"contact", EncodeArray(contact)}};

  // B's field, on a plane through A's origin that contains (nearly) the line between the
  // bodies: its normal is the axis of B's frame along which A's origin is closest.
  const Eigen::Vector3d p_BA = X_WB.Inverse() * X_WA.translation;
  int axis = options.slice_axis;
  if (axis < 0) {
    axis = 0;
    for (int a = 1; a < 3; ++a)
      if (std::abs(p_BA[a]) < std::abs(p_BA[axis])) axis = a;
  }
  const FieldSlice s = SliceField(*field, axis, options.slice_at.value_or(p_BA[axis]), options.max_slice_side);
  const auto [lo, hi] = std::minmax_element(s.values.begin(), s.values.end());
  j["slice"] = {{"body", 1},
                {"axis", s.axis},
                {"at", s.at},
                {"width", s.width},
                {"height", s.height},
                {"corner", Vector3Json(s.corner)},
                {"u", Vector3Json(s.u)},
                {"v", Vector3Json(s.v)},
                {"spacing", field->spacing()},
                {"min", *lo},
                {"max", *hi},
                {"values", EncodeArray(s.values)}};
  return j;
}

// Contact surfaces per model page data: at most this many triangles in all.
constexpr int kSurfaceTrianglesPerModel = 200000;

// Whether model NAME keeps a contact surface for display (its registry entry says so).
bool KeepsContactSurface(const std::string& name) {
  const ContactModelEntry* entry = FindContactModel(name);
  return entry != nullptr && entry->contact_surface;
}

// Evaluates MODEL (keeping its surface) at QUERY and appends the surface's corners and
// pressures to *CORNERS and *PRESSURE; *SCRATCH holds it on the way. Returns its triangles.
std::size_t AppendSurfaceAt(ContactModel& model, const ContactQuery& query, ContactSurface* scratch,
                            std::vector<float>* corners, std::vector<float>* pressure) {
  model.Evaluate(query);
  model.LatestContactSurface(scratch);
  for (const Eigen::Vector3f& c : scratch->corners) corners->insert(corners->end(), {c.x(), c.y(), c.z()});
  pressure->insert(pressure->end(), scratch->pressure.begin(), scratch->pressure.end());
  return scratch->corners.size() / 3;
}

float MaxOf(const std::vector<float>& v) { return v.empty() ? 0.0f : *std::max_element(v.begin(), v.end()); }

}  // namespace

namespace {

// Each body of SCENE (a scene of many bodies) as assets of its own, its meshes found beside the
// scene's file.
std::vector<std::unique_ptr<BodyAssets>> OwnBodies(const Scene& scene, const AssetOptions& assets) {
  if (!scene.many_bodies()) Fail(scene.file, "is a scene of two bodies (no tool)");
  AssetOptions beside = assets;
  if (beside.mesh_dir.empty() && !scene.file.empty()) beside.mesh_dir = FolderOf(scene.file);
  std::vector<std::unique_ptr<BodyAssets>> bodies;
  for (const BodySpec& b : scene.bodies) bodies.push_back(std::make_unique<BodyAssets>(b, beside));
  return bodies;
}

std::vector<BodyAssets*> Pointers(const std::vector<std::unique_ptr<BodyAssets>>& owned) {
  std::vector<BodyAssets*> p;
  for (const auto& b : owned) p.push_back(b.get());
  return p;
}

// ManyBodiesViewData with the tool at X_W_TOOL and the mesh drawn of each body in *MESHES.
nlohmann::json ManyBodiesViewDataAndMeshes(const Scene& scene, const std::string& default_model,
                                           const std::vector<BodyAssets*>& bodies, const SceneViewOptions& options,
                                           const Pose& X_W_tool, std::vector<TriangleMesh>* meshes) {
  if (!scene.many_bodies()) Fail(scene.file, "is a scene of two bodies (no tool)");
  if (bodies.size() != scene.bodies.size()) {
    Fail(scene.file, "view: " + std::to_string(bodies.size()) + " bodies' assets for " +
                         std::to_string(scene.bodies.size()) + " bodies");
  }
  nlohmann::json j;
  j["title"] = scene.name;
  j["scene"] = scene.file;
  j["tool"] = scene.tool;
  j["bodies"] = nlohmann::json::array();
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    meshes->push_back(DisplayMesh(*bodies[i], options.max_triangles));
    const bool tool = int(i) == scene.tool;
    nlohmann::json b = BodyJson(*bodies[i], tool ? X_W_tool : scene.bodies[i].pose, meshes->back());
    b["tool"] = tool;
    j["bodies"].push_back(std::move(b));
  }
  j["pairs"] = nlohmann::json::array();
  for (const PairSpec& pair : scene.pairs) {
    const OrderedPair o = OrderPair(scene, pair, default_model);
    j["pairs"].push_back({{"bodies", {scene.bodies[std::size_t(o.A)].name, scene.bodies[std::size_t(o.B)].name}},
                          {"model", o.model}});
  }
  return j;
}

}  // namespace

nlohmann::json ManyBodiesViewData(const Scene& scene, const std::string& default_model,
                                  const std::vector<BodyAssets*>& bodies, const SceneViewOptions& options) {
  std::vector<TriangleMesh> meshes;
  const Pose X_W_tool = scene.many_bodies() ? scene.bodies[std::size_t(scene.tool)].pose : Pose{};
  return ManyBodiesViewDataAndMeshes(scene, default_model, bodies, options, X_W_tool, &meshes);
}

nlohmann::json ManyBodiesViewData(const Scene& scene, const std::string& default_model, const AssetOptions& assets,
                                  const SceneViewOptions& options) {
  const std::vector<std::unique_ptr<BodyAssets>> bodies = OwnBodies(scene, assets);
  return ManyBodiesViewData(scene, default_model, Pointers(bodies), options);
}

nlohmann::json SceneViewData(const Scene& scene, SceneAssets& assets, const SceneViewOptions& options,
                             const std::optional<BodyPoses>& poses) {
  std::array<TriangleMesh, 2> meshes;
  nlohmann::json j = SceneViewDataAndMeshes(scene, assets, options, poses, &meshes);
  j["surfaces"] = nlohmann::json::array();
  for (const std::string& name : scene.models) {
    if (!KeepsContactSurface(name)) continue;
    const auto model = MakeSceneContactModel(name, scene, assets);
    const int cap = std::max(1, options.max_surface_triangles);
    model->KeepContactSurface(cap);
    const ContactQuery q = SceneContactQuery(scene, poses ? poses->X_WA : scene.pointshell_body.pose,
                                             poses ? poses->X_WB : scene.field_body.pose);
    ContactSurface scratch;
    std::vector<float> corners, pressure;
    const std::size_t triangles = AppendSurfaceAt(*model, q, &scratch, &corners, &pressure);
    j["surfaces"].push_back({{"model", name},
                             {"triangles", triangles},
                             {"max_triangles", cap},
                             {"corners", EncodeArray(corners)},
                             {"pressure", EncodeArray(pressure)},
                             {"pmax", MaxOf(pressure)}});
  }
  return j;
}

namespace {

// The contact surface of TRACK's model at up to OPTIONS.max_surface_frames of its frames (evenly
// spaced, the first and the last among them), the model evaluated again at the recorded poses
// with the other body where the scene puts it; null when the model keeps no surface.
nlohmann::json TrackSurface(const Replay& replay, const ReplayTrack& track, bool moving_is_B, SceneAssets& assets,
                            const SceneViewOptions& options) {
  const int frames = int(track.t.size());
  if (!KeepsContactSurface(track.model) || frames == 0 || options.max_surface_frames <= 0) return nullptr;
  const auto model = MakeSceneContactModel(track.model, replay.scene, assets);
  const int n = std::min(frames, options.max_surface_frames);
  const int cap = std::max(1, std::min(options.max_surface_triangles, kSurfaceTrianglesPerModel / n));
  model->KeepContactSurface(cap);
  std::vector<std::int32_t> kept;
  std::vector<std::uint32_t> start{0};
  std::vector<float> corners, pressure;
  ContactSurface s;
  for (int k = 0; k < n; ++k) {
    const int f = n == 1 ? 0 : int(std::llround(double(k) * (frames - 1) / (n - 1)));
    const float* p = track.pose.data() + 7 * std::size_t(f);
    const Pose X{Eigen::Quaterniond(p[3], p[4], p[5], p[6]).normalized(), Eigen::Vector3d(p[0], p[1], p[2])};
    const ContactQuery q = SceneContactQuery(replay.scene, moving_is_B ? replay.scene.pointshell_body.pose : X,
                                             moving_is_B ? X : replay.scene.field_body.pose, f);
    AppendSurfaceAt(*model, q, &s, &corners, &pressure);
    kept.push_back(f);
    start.push_back(std::uint32_t(corners.size() / 9));
  }
  return {{"frames", EncodeArray(kept)},
          {"start", EncodeArray(start)},
          {"corners", EncodeArray(corners)},
          {"pressure", EncodeArray(pressure)},
          {"pmax", MaxOf(pressure)},
          {"max_triangles", cap}};
}

}  // namespace

namespace {

// ReadReplay's steps, in the order it takes them.

// The two files of results folder DIR: cycles.csv and meta.json. Throws Error naming the
// folder or the file that is missing, or the folder when it holds a deformed-field study.
struct ResultsFiles {
  fs::path cycles, meta;
  fs::path bodies;  // a many-bodies study's world_bodies.csv (else empty)
};
ResultsFiles CheckResultsFolder(const fs::path& dir) {
  if (!fs::is_directory(dir)) {
    Fail(dir.string(), fs::exists(dir) ? "is not a results folder (expected a folder holding cycles.csv and meta.json)"
                                       : "results folder not found");
  }
  const fs::path meta_file = dir / "meta.json";
  if (!fs::exists(meta_file)) Fail(meta_file.string(), "not found (a results folder holds cycles.csv and meta.json)");
  // The study that wrote the folder says whether it holds trajectories (experiment/study.h),
  // in its first table.
  const Study& study = StudyOfResults(dir);
  if (!study.replayable) {
    Fail(dir.string(), "holds a " + study.name + " study (" + study.description + "), which has no trajectory to replay");
  }
  ResultsFiles files{dir / study.tables.front().file, meta_file, {}};
  if (study.many_bodies) files.bodies = dir / study.tables.at(2).file;
  for (const fs::path& f : {files.cycles, files.bodies}) {
    if (!f.empty() && !fs::exists(f)) {
      Fail(f.string(), "not found (a results folder of study: " + study.name + " holds it and meta.json)");
    }
  }
  return files;
}

// What meta.json says of the run: its resolved config (YAML text) and the config file it was
// read from (meta.json itself when it does not say).
struct ResolvedConfig {
  std::string yaml;
  std::string file;
};
ResolvedConfig ReadResolvedConfig(const fs::path& meta_file) {
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(ReadWholeFile(meta_file));
  } catch (const nlohmann::json::exception& e) {
    Fail(meta_file.string(), std::string("not valid JSON: ") + e.what());
  }
  if (!meta.is_object() || !meta.contains("resolved_config") || !meta["resolved_config"].is_string()) {
    Fail(meta_file.string(), "has no resolved_config (not written by contactlab run)");
  }
  return {meta["resolved_config"].get<std::string>(), meta.value("config_file", meta_file.string())};
}

// One cycle of one model, as the replay keeps it.
struct ReplayRow {
  int job = 0;
  std::string model;
  double v[16];  // t, pose x,y,z,qw,qx,qy,qz, force (3), torque (3), level, contacts
  std::vector<float> q, q_B;  // deformable bodies' reduced coordinates (empty when rigid)
  std::vector<std::pair<std::string, std::vector<float>>> bodies_q;  // a scene of many bodies: (body, q)
};

// The rows of cycles.csv kept for the replay: those of JOB (of every job when none is asked
// for), with the jobs the file holds and the experiment's name of each job kept (of its first
// row).
struct CycleRows {
  std::vector<ReplayRow> rows;
  std::set<int> jobs;
  std::map<int, std::string> experiment;
};
CycleRows ReadCycleRows(const fs::path& cycles_file, std::optional<int> job) {
  CycleRows out;
  ReadCyclesCsv(cycles_file, [&](const CyclesCsvRow& c) {
    out.jobs.insert(c.job);
    if (job && c.job != *job) return;
    out.experiment.try_emplace(c.job, c.experiment);
    const CycleRow& x = c.values;
    ReplayRow r;
    r.job = c.job;
    r.model = c.model;
    r.v[0] = x.t;
    for (int k = 0; k < 3; ++k) r.v[1 + k] = x.position[k];
    r.v[4] = x.rotation.w(), r.v[5] = x.rotation.x(), r.v[6] = x.rotation.y(), r.v[7] = x.rotation.z();
    for (int k = 0; k < 3; ++k) r.v[8 + k] = x.force[k];
    for (int k = 0; k < 3; ++k) r.v[11 + k] = x.torque[k];
    r.v[14] = x.level;
    r.v[15] = x.contacts;
    r.q.assign(c.q.begin(), c.q.end());
    r.q_B.assign(c.q_B.begin(), c.q_B.end());
    out.rows.push_back(std::move(r));
  });
  return out;
}

// The cells of the CSV text TEXT (FILE) as {column: cell} per record, calling ROW for each; a
// column NEEDS names that the header lacks, or a record of another length, is an Error naming
// the file (and line).
void ForEachCsvRecord(const std::string& text, const fs::path& file, const std::vector<std::string>& needs,
                      const std::function<void(const std::map<std::string, std::size_t>&,
                                               const std::vector<std::string>&, long)>& row) {
  CsvReader reader(text, file.string());
  std::vector<std::string> header, cells;
  if (!reader.Next(&header)) Fail(file.string(), "is empty (no header)");
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column[header[i]] = i;
  for (const std::string& c : needs) {
    if (!column.count(c)) FailAtLine(file.string(), 1, "has no column '" + c + "'");
  }
  while (reader.Next(&cells)) {
    if (cells.size() != header.size()) {
      FailAtLine(file.string(), reader.line(),
                 std::to_string(cells.size()) + " cells, the header has " + std::to_string(header.size()));
    }
    row(column, cells, reader.line());
  }
}

double CellNumber(const std::string& cell, const fs::path& file, long line, const std::string& column) {
  const std::optional<double> v = ParseDouble(cell);
  if (!v) FailAtLine(file.string(), line, "column " + column + ": '" + cell + "' is not a finite number");
  return *v;
}

// The rows of a many-bodies study's world_cycles.csv (FILES.cycles) kept for the replay, as
// ReadCycleRows keeps cycles.csv's, and each deformable body's q of the same cycle from
// world_bodies.csv (FILES.bodies).
CycleRows ReadWorldRows(const ResultsFiles& files, std::optional<int> job) {
  CycleRows out;
  const std::vector<std::string> columns = {"experiment", "job", "model", "cycle", "t", "x", "y", "z", "qw", "qx", "qy",
                                            "qz", "fx", "fy", "fz", "tx", "ty", "tz", "contacts"};
  std::map<std::tuple<int, std::string, long long>, std::size_t> row_of;  // (job, model, cycle) -> row
  const std::string cycles_text = ReadWholeFile(files.cycles);
  ForEachCsvRecord(cycles_text, files.cycles, columns, [&](const auto& col, const auto& cells, long line) {
    auto number = [&](const char* c) { return CellNumber(cells[col.at(c)], files.cycles, line, c); };
    const int j = int(number("job"));
    out.jobs.insert(j);
    if (job && j != *job) return;
    out.experiment.try_emplace(j, cells[col.at("experiment")]);
    ReplayRow r;
    r.job = j;
    r.model = cells[col.at("model")];
    for (std::size_t k = 0; k < 14; ++k) r.v[k] = number(columns[4 + k].c_str());
    r.v[14] = -1;  // the level: a tree's, not a world's
    r.v[15] = number("contacts");
    row_of[{j, r.model, (long long)number("cycle")}] = out.rows.size();
    out.rows.push_back(std::move(r));
  });
  const std::string bodies_text = ReadWholeFile(files.bodies);
  ForEachCsvRecord(bodies_text, files.bodies, {"job", "model", "cycle", "body", "q"},
                   [&](const auto& col, const auto& cells, long line) {
    const int j = int(CellNumber(cells[col.at("job")], files.bodies, line, "job"));
    const long long cycle = (long long)CellNumber(cells[col.at("cycle")], files.bodies, line, "cycle");
    const auto it = row_of.find({j, cells[col.at("model")], cycle});
    if (it == row_of.end()) {
      if (job && j != *job) return;
      FailAtLine(files.bodies.string(), line, "names a cycle that world_cycles.csv does not hold");
    }
    std::vector<float> q;
    std::istringstream in(cells[col.at("q")]);
    for (std::string v; in >> v;) q.push_back(float(CellNumber(v, files.bodies, line, "q")));
    out.rows[it->second].bodies_q.emplace_back(cells[col.at("body")], std::move(q));
  });
  return out;
}

// The job to replay among JOBS (those of CYCLES_FILE): the one asked for, or with none asked
// for the only one. Throws Error naming the file when there is none, or several and none was
// asked for, or the one asked for is absent.
int PickJob(const std::set<int>& jobs, std::optional<int> job, const fs::path& cycles_file) {
  auto job_list = [&] {
    std::string s;
    for (int j : jobs) s += (s.empty() ? "" : ", ") + std::to_string(j);
    return s;
  };
  if (jobs.empty()) Fail(cycles_file.string(), "has no rows");
  if (!job) {
    if (jobs.size() > 1) Fail(cycles_file.string(), "holds jobs " + job_list() + ": choose one with --job");
    return *jobs.begin();
  }
  if (!jobs.count(*job)) Fail(cycles_file.string(), "has no job " + std::to_string(*job) + " (it holds " + job_list() + ")");
  return *job;
}

// The ROWS of job JOB by model, the models in order of first appearance.
std::vector<std::pair<std::string, std::vector<const ReplayRow*>>> RowsByModel(const std::vector<ReplayRow>& rows,
                                                                               int job) {
  std::vector<std::pair<std::string, std::vector<const ReplayRow*>>> models;
  std::map<std::string, std::size_t> index;
  for (const ReplayRow& r : rows) {
    if (r.job != job) continue;
    const auto [it, added] = index.try_emplace(r.model, models.size());
    if (added) models.emplace_back(r.model, std::vector<const ReplayRow*>{});
    models[it->second].second.push_back(&r);
  }
  return models;
}

// The stride that leaves no model with more than MAX_FRAMES of its cycles (every STRIDE-th
// kept, the first always).
int StrideFor(const std::vector<std::pair<std::string, std::vector<const ReplayRow*>>>& models, int max_frames) {
  std::size_t longest = 0;
  for (const auto& [name, rows] : models) longest = std::max(longest, rows.size());
  return std::max(1, int((longest + std::size_t(max_frames) - 1) / std::size_t(max_frames)));
}

// The track of model NAME from its ROWS (one per cycle, at least one), every STRIDE-th kept.
ReplayTrack MakeTrack(const std::string& name, const std::vector<const ReplayRow*>& rows, int stride) {
  ReplayTrack track;
  track.model = name;
  track.cycles = std::int64_t(rows.size());
  // Reduced coordinates: as many in every row of the model as in its first (ReadCyclesCsv
  // checks it).
  track.r = int(rows.front()->q.size());
  track.r_B = int(rows.front()->q_B.size());
  for (std::size_t i = 0; i < rows.size(); i += std::size_t(stride)) {
    const double* x = rows[i]->v;
    track.t.push_back(float(x[0]));
    for (int k = 0; k < 7; ++k) track.pose.push_back(float(x[1 + k]));
    for (int k = 0; k < 3; ++k) track.force.push_back(float(x[8 + k]));
    for (int k = 0; k < 3; ++k) track.torque.push_back(float(x[11 + k]));
    track.level.push_back(std::int32_t(x[14]));
    track.contacts.push_back(std::int32_t(x[15]));
    track.q.insert(track.q.end(), rows[i]->q.begin(), rows[i]->q.end());
    track.q_B.insert(track.q_B.end(), rows[i]->q_B.begin(), rows[i]->q_B.end());
    // A scene of many bodies: every kept row holds the bodies of the first, as many coordinates
    // each.
    for (const auto& [body, q] : rows[i]->bodies_q) {
      auto b = std::find_if(track.bodies_q.begin(), track.bodies_q.end(),
                            [&](const ReplayTrack::BodyCoordinates& c) { return c.body == body; });
      if (b == track.bodies_q.end()) {
        if (i > 0) continue;  // a body the first frame lacks is not replayed
        b = track.bodies_q.insert(track.bodies_q.end(), {body, int(q.size()), {}});
      }
      if (int(q.size()) == b->r) b->q.insert(b->q.end(), q.begin(), q.end());
    }
  }
  // Bodies missing from some frame, or with coordinates of another length, are shown at rest.
  const std::size_t frames = track.t.size();
  std::erase_if(track.bodies_q, [&](const ReplayTrack::BodyCoordinates& c) {
    return c.q.size() != frames * std::size_t(c.r);
  });
  return track;
}

// REPLAY's scene, moving body and job label (and its experiment's name when cycles.csv gave
// none), from the RESOLVED config expanded again to the job REPLAY->job. Throws Error naming
// META_FILE when the config's study has no trajectories to replay (Study::replayable) or the
// config has no such job.
void SetJobScene(const ResolvedConfig& resolved, const fs::path& meta_file, Replay* replay) {
  const ConfigNode root = ConfigNode::LoadString(resolved.yaml, resolved.file);
  const ExperimentConfig config = ParseExperimentConfig(root, resolved.yaml, resolved.yaml);
  if (!StudyOf(config).replayable) {
    Fail(meta_file.string(), "is a " + config.study + " study, which has no trajectory to replay");
  }
  const std::size_t total = JobCount(config);
  if (replay->job < 0 || std::size_t(replay->job) >= total) {
    Fail(meta_file.string(), "its config has " + std::to_string(total) + " jobs, cycles.csv names job " +
                                 std::to_string(replay->job));
  }
  const Job job = ExpandJob(config, std::size_t(replay->job));
  replay->scene = job.scene;
  replay->moving_body = job.moving_body;
  replay->job_label = job.axis_values.empty() ? "" : job.Label();
  if (replay->experiment.empty()) replay->experiment = config.name;
}

}  // namespace

namespace {

// The replay of job JOB of results folder DIR from its CYCLES rows and its resolved CONFIG.
Replay MakeReplay(const fs::path& dir, const ResultsFiles& files, const ResolvedConfig& config,
                  const CycleRows& cycles, int job, int max_frames) {
  Replay replay;
  replay.dir = dir;
  if (const auto it = cycles.experiment.find(job); it != cycles.experiment.end()) replay.experiment = it->second;
  replay.job = job;
  // One track per model, thinned to MAX_FRAMES.
  const auto models = RowsByModel(cycles.rows, job);
  replay.stride = StrideFor(models, max_frames);
  for (const auto& [name, rows] : models) replay.tracks.push_back(MakeTrack(name, rows, replay.stride));
  SetJobScene(config, files.meta, &replay);
  return replay;
}

}  // namespace

Replay ReadReplay(const fs::path& dir, std::optional<int> job, int max_frames) {
  const ResultsFiles files = CheckResultsFolder(dir);
  if (max_frames < 2) Fail("--max-frames", "must be at least 2, got " + std::to_string(max_frames));
  const ResolvedConfig config = ReadResolvedConfig(files.meta);
  const CycleRows cycles = files.bodies.empty() ? ReadCycleRows(files.cycles, job) : ReadWorldRows(files, job);
  return MakeReplay(dir, files, config, cycles, PickJob(cycles.jobs, job, files.cycles), max_frames);
}

std::vector<Replay> ReadReplays(const fs::path& dir, int max_frames) {
  const ResultsFiles files = CheckResultsFolder(dir);
  if (max_frames < 2) Fail("--max-frames", "must be at least 2, got " + std::to_string(max_frames));
  const ResolvedConfig config = ReadResolvedConfig(files.meta);
  const CycleRows cycles =
      files.bodies.empty() ? ReadCycleRows(files.cycles, std::nullopt) : ReadWorldRows(files, std::nullopt);
  if (cycles.jobs.empty()) Fail(files.cycles.string(), "has no rows");
  std::vector<Replay> replays;
  for (int job : cycles.jobs) replays.push_back(MakeReplay(dir, files, config, cycles, job, max_frames));
  return replays;
}

namespace {

// The reduced basis (r modes) of deformable BODY at the vertices of MESH (the mesh drawn) into
// its page data *J ("modes", "basis"), or "basis_omitted" beyond 16 million entries.
void AddBasis(BodyAssets& body, const TriangleMesh& mesh, int r, nlohmann::json* j) {
  const auto model = body.reduced_model();
  if (double(mesh.num_vertices()) * 3 * r > 16e6) {
    (*j)["basis_omitted"] = true;
    return;
  }
  const EmbeddedPoints points(model->mesh, model->basis, mesh.vertices, {}, GradientScheme::kSmooth);
  std::vector<float> basis;
  basis.reserve(std::size_t(mesh.num_vertices()) * 3 * r);
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    const Eigen::MatrixXd U = points.Basis(v);  // 3 x r
    for (int k = 0; k < 3; ++k)
      for (int m = 0; m < r; ++m) basis.push_back(float(U(k, m)));
  }
  (*j)["modes"] = r;
  (*j)["basis"] = EncodeArray(basis);
}

// The tool's pose at the first frame of REPLAY's first model (DEFAULT when it has none).
Pose FirstPose(const Replay& replay, const Pose& fallback) {
  if (replay.tracks.empty() || replay.tracks.front().t.empty()) return fallback;
  const float* p = replay.tracks.front().pose.data();
  return Pose{Eigen::Quaterniond(p[3], p[4], p[5], p[6]).normalized(), Eigen::Vector3d(p[0], p[1], p[2])};
}

// One track as the page reads it (an entry of replay.models), without the coordinates of
// deformable bodies.
nlohmann::json TrackJson(const ReplayTrack& t) {
  return {{"name", t.model},
          {"cycles", t.cycles},
          {"frames", t.t.size()},
          {"t", EncodeArray(t.t)},
          {"pose", EncodeArray(t.pose)},
          {"force", EncodeArray(t.force)},
          {"torque", EncodeArray(t.torque)},
          {"level", EncodeArray(t.level)},
          {"contacts", EncodeArray(t.contacts)}};
}

nlohmann::json ReplayJson(const Replay& replay, int moving, nlohmann::json models) {
  return {{"experiment", replay.experiment},
          {"folder", replay.dir.string()},
          {"job", replay.job},
          {"label", replay.job_label},
          {"moving", moving},
          {"moving_body", replay.moving_body},
          {"stride", replay.stride},
          {"models", std::move(models)}};
}

}  // namespace

nlohmann::json WorldReplayViewData(const Replay& replay, const AssetOptions& assets, const SceneViewOptions& options) {
  const Scene& scene = replay.scene;
  if (!scene.many_bodies()) Fail(replay.dir.string(), "its scene is one of two bodies: a replay of study: contact");
  const std::vector<std::unique_ptr<BodyAssets>> bodies = OwnBodies(scene, assets);
  std::vector<TriangleMesh> meshes;
  const Pose X_W_tool = FirstPose(replay, scene.bodies[std::size_t(scene.tool)].pose);
  const std::string default_model = replay.tracks.empty() ? scene.models.front() : replay.tracks.front().model;
  nlohmann::json j = ManyBodiesViewDataAndMeshes(scene, default_model, Pointers(bodies), options, X_W_tool, &meshes);
  // Each deformable body's coordinates, which must fit its reduced model.
  auto index_of = [&](const std::string& name) {
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
      if (scene.bodies[i].name == name) return int(i);
    }
    return -1;
  };
  const std::string bodies_file = (replay.dir / "world_bodies.csv").string();
  std::vector<int> modes(scene.bodies.size(), 0);
  nlohmann::json models = nlohmann::json::array();
  for (const ReplayTrack& t : replay.tracks) {
    nlohmann::json m = TrackJson(t);
    m["bodies_q"] = nlohmann::json::array();
    for (const ReplayTrack::BodyCoordinates& c : t.bodies_q) {
      const int b = index_of(c.body);
      if (b < 0) Fail(bodies_file, "model " + t.model + ": no body '" + c.body + "' in the scene");
      BodyAssets& body = *bodies[std::size_t(b)];
      const int body_r = body.deformable() ? body.reduced_model()->r() : 0;
      if (c.r != body_r) {
        Fail(bodies_file, "model " + t.model + " holds " + std::to_string(c.r) + " reduced coordinates of body '" +
                              c.body + "', " +
                              (body.deformable() ? "whose model has r = " + std::to_string(body_r) : "which is rigid"));
      }
      modes[std::size_t(b)] = c.r;
      m["bodies_q"].push_back({{"body", b}, {"r", c.r}, {"q", EncodeArray(c.q)}});
    }
    models.push_back(std::move(m));
  }
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (modes[b] > 0) AddBasis(*bodies[b], meshes[b], modes[b], &j["bodies"][b]);
  }
  j["title"] = replay.experiment + (replay.job_label.empty() ? "" : " — " + replay.job_label);
  j["replay"] = ReplayJson(replay, scene.tool, std::move(models));
  return j;
}

nlohmann::json ReplayViewData(const Replay& replay, SceneAssets& assets, const SceneViewOptions& options) {
  const bool moving_is_B = replay.moving_body == replay.scene.field_body.name;
  // Bodies at the first frame of the first model: the moving body where the trajectory starts.
  BodyPoses poses{replay.scene.pointshell_body.pose, replay.scene.field_body.pose};
  if (!replay.tracks.empty() && !replay.tracks.front().t.empty()) {
    const float* p = replay.tracks.front().pose.data();
    const Pose X{Eigen::Quaterniond(p[3], p[4], p[5], p[6]).normalized(), Eigen::Vector3d(p[0], p[1], p[2])};
    (moving_is_B ? poses.X_WB : poses.X_WA) = X;
  }
  std::array<TriangleMesh, 2> meshes;
  nlohmann::json j = SceneViewDataAndMeshes(replay.scene, assets, options, poses, &meshes);

  // Deformable bodies with recorded coordinates: the reduced basis at their mesh vertices.
  for (int b = 0; b < 2; ++b) {
    BodyAssets& body = b == 0 ? assets.A : assets.B;
    // Every model's recorded coordinates must fit the body: r of its reduced model, none when
    // it is rigid.
    int r = 0;
    for (const ReplayTrack& t : replay.tracks) {
      const int track_r = b == 0 ? t.r : t.r_B;
      if (track_r == 0) continue;
      const int body_r = body.deformable() ? body.reduced_model()->r() : 0;
      if (track_r != body_r) {
        Fail((replay.dir / "cycles.csv").string(),
             "model " + t.model + " holds " + std::to_string(track_r) + " reduced coordinates (column " +
                 (b == 0 ? "q" : "q_B") + ") of body '" + body.spec().name + "', " +
                 (body.deformable() ? "whose model has r = " + std::to_string(body_r) : "which is rigid"));
      }
      r = track_r;
    }
    if (r > 0) AddBasis(body, meshes[b], r, &j["bodies"][b]);
  }

  j["title"] = replay.experiment + (replay.job_label.empty() ? "" : " — " + replay.job_label);
  nlohmann::json models = nlohmann::json::array();
  for (const ReplayTrack& t : replay.tracks) {
    models.push_back(TrackJson(t));
    models.back()["r"] = t.r;
    models.back()["q"] = EncodeArray(t.q);
    models.back()["r_B"] = t.r_B;
    models.back()["q_B"] = EncodeArray(t.q_B);
    if (nlohmann::json surface = TrackSurface(replay, t, moving_is_B, assets, options); !surface.is_null()) {
      models.back()["surface"] = std::move(surface);
    }
  }
  j["replay"] = ReplayJson(replay, moving_is_B ? 1 : 0, std::move(models));
  return j;
}

namespace {

// Strings of the page data at least this long (base64 arrays: meshes, pointshells, slices) are
// embedded once however many jobs hold them.
constexpr std::size_t kMinSharedString = 1024;

// Replaces every string of J of at least kMinSharedString characters by {"$blob": N}, N its
// index in *BLOBS (added there the first time that text is met; *INDEX: text -> N).
void ShareLongStrings(nlohmann::json* j, std::vector<std::string>* blobs, std::map<std::string, int>* index) {
  if (j->is_string()) {
    const std::string& text = j->get_ref<const std::string&>();
    if (text.size() < kMinSharedString) return;
    const auto [it, added] = index->try_emplace(text, int(blobs->size()));
    if (added) blobs->push_back(text);
    *j = nlohmann::json{{"$blob", it->second}};
  } else if (j->is_structured()) {
    for (nlohmann::json& item : *j) ShareLongStrings(&item, blobs, index);
  }
}

}  // namespace

nlohmann::json SeveralJobsViewData(const std::vector<Replay>& replays, std::vector<nlohmann::json> job_data) {
  if (replays.empty() || replays.size() != job_data.size()) {
    Fail("view", "SeveralJobsViewData needs one page data per replay, got " + std::to_string(job_data.size()) +
                     " for " + std::to_string(replays.size()));
  }
  nlohmann::json jobs = nlohmann::json::array();
  std::vector<std::string> blobs;
  std::map<std::string, int> index;
  for (std::size_t i = 0; i < replays.size(); ++i) {
    jobs.push_back({{"job", replays[i].job},
                    {"label", replays[i].job_label},
                    {"title", job_data[i].value("title", replays[i].experiment)}});
    ShareLongStrings(&job_data[i], &blobs, &index);
  }
  return {{"title", replays.front().experiment},
          {"jobs", std::move(jobs)},
          {"blobs", std::move(blobs)},
          {"job_data", std::move(job_data)}};
}

}  // namespace contactlab
