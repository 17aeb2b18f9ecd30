// The data the viewer page shows, as JSON (base64 arrays, page_encoding.h): the bodies of a
// scene (two, or many: ManyBodiesViewData) (meshes in their body frames and start poses), the pointshell of the pointshell body
// coloured by level (Barbič & James 2008, sec. 2.2, 2.4), a slice of the field body's signed
// distance field (sec. 2.3), and for a replay the per-cycle poses and wrenches of each model.
// The viewer's modules (src/view/web/viewer/) read it; docs/viewer.md describes the page.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "scene/scene_assets.h"

namespace contactlab {

struct SceneViewOptions {
  int max_points = 50000;          // pointshell points drawn at most (display_points.h)
  int max_triangles = 50000;       // triangles drawn per body at most: larger meshes are thinned
                                   // by edge collapse (CGAL builds); <= 0: all
  int slice_axis = -1;             // field slice normal in the field body's frame: 0..2, -1 automatic
  std::optional<double> slice_at;  // the slice's coordinate along slice_axis (body frame, metres);
                                   // none: through the pointshell body's origin
  int max_slice_side = 512;        // slice samples per side at most
  // Contact surfaces (models whose registry entry has contact_surface: pressure-field): the
  // scene page draws those of the scene's models at its poses; a replay keeps each such model's
  // surface at up to MAX_SURFACE_FRAMES of its frames, evenly spaced, evaluated again at the
  // recorded poses. At most MAX_SURFACE_TRIANGLES triangles per surface, and 200,000 per model
  // in all (fewer per frame when many frames are kept); the rest of a larger surface is not drawn.
  int max_surface_frames = 200;
  int max_surface_triangles = 20000;
};

// Start poses of the bodies when they differ from the scene's (a replay's first cycle).
struct BodyPoses {
  Pose X_WA, X_WB;  // pointshell body A, field body B
};

// {"title", "scene", "bodies": [A, B] each {"name", "role", "pose": [x,y,z,qw,qx,qy,qz],
// "positions": f32 (#V x 3), "indices": u32 (#T x 3), "vertices", "triangles" (drawn),
// "source_triangles" (of the body's mesh)},
// "pointshell": {"body": 0, "positions", "level": u8, "kept": [...], "total": [...],
// "in_contact": points of the whole shell with d < 0 in B's field at these poses, "contact": u8
// per drawn point (1: d < 0)},
// "slice": {"body": 1, "axis", "at", "width", "height", "corner", "u", "v", "values": f32,
// "min", "max", "spacing"},
// "surfaces": [{"model", "triangles", "max_triangles", "corners": f32 (#T x 3 x 3, world),
// "pressure": f32 (#T x 3, Pa), "pmax"}] of the scene's models that keep one (empty for the
// others)}. Builds (or reads from the cache) A's pointshell and B's field, and what those models
// need.
nlohmann::json SceneViewData(const Scene& scene, SceneAssets& assets, const SceneViewOptions& options,
                             const std::optional<BodyPoses>& poses = std::nullopt);

// A scene of many bodies (Scene::many_bodies): {"title", "scene", "bodies": [every body as
// SceneViewData gives one, in the scene's order, the tool with "tool": true], "tool": its index,
// "pairs": [{"bodies": [A's name, B's name] in the pair's model's order, "model"}]}, each pair
// without a model of its own taking DEFAULT_MODEL. Meshes only (no pointshell, slice or contact
// surface: those belong to a pair, and a pair's are not built for the page). Builds (or reads)
// each body's mesh through OPTIONS_ASSETS, its meshes found beside the scene's file.
nlohmann::json ManyBodiesViewData(const Scene& scene, const std::string& default_model, const AssetOptions& assets,
                                  const SceneViewOptions& options);
// The same from the bodies' assets BODIES (one per body of the scene, in its order: a
// SceneWorld's, so a live session loads no mesh again). Throws Error for another count.
nlohmann::json ManyBodiesViewData(const Scene& scene, const std::string& default_model,
                                  const std::vector<BodyAssets*>& bodies, const SceneViewOptions& options);

// One model's run in a results folder, thinned to at most the requested number of frames.
struct ReplayTrack {
  std::string model;
  std::vector<float> t;             // (#F) seconds
  std::vector<float> pose;          // (#F x 7) moving body x,y,z,qw,qx,qy,qz, world
  std::vector<float> force;         // (#F x 3) on the moving body, world, N
  std::vector<float> torque;        // (#F x 3) on the moving body about its origin, N m
  std::vector<std::int32_t> level;  // (#F) level rendered (-1: not a pointshell model)
  std::vector<std::int32_t> contacts;  // (#F) points or contacts
  std::int64_t cycles = 0;          // rows in cycles.csv before thinning
  // Deformable bodies (paper sec. 4): reduced coordinates after each kept cycle, from the
  // columns q (body A) and q_B (body B); empty for a rigid body.
  int r = 0, r_B = 0;
  std::vector<float> q;             // (#F x r)
  std::vector<float> q_B;           // (#F x r_B)
  // A scene of many bodies (study: many-bodies, world_bodies.csv): each deformable body's
  // reduced coordinates after each kept cycle.
  struct BodyCoordinates {
    std::string body;               // its name
    int r = 0;
    std::vector<float> q;           // (#F x r)
  };
  std::vector<BodyCoordinates> bodies_q;
};

struct Replay {
  std::filesystem::path dir;
  std::string experiment;
  int job = 0;
  std::string job_label;            // "points=1024 model=vps", empty without a sweep
  Scene scene;                      // the job's scene (sweep values applied)
  std::string moving_body;          // name of the body that followed the trajectory
  std::vector<ReplayTrack> tracks;  // one per model, in the order of cycles.csv
  int stride = 1;                   // every STRIDE-th cycle kept
};

// Reads results folder DIR (cycles.csv, meta.json; of a many-bodies study world_cycles.csv and
// world_bodies.csv, the tool being the moving body) for job JOB (none: the only job it holds),
// keeping every k-th cycle so no model has more than MAX_FRAMES frames. The job's scene comes
// from meta.json's resolved config. Throws Error naming the file and what is wrong: a missing
// folder or file, a deformed-field study, a cycles.csv that ReadCyclesCsv refuses (result_csv.h;
// one without the orientation columns was written before they were added), several jobs and
// no JOB, an unknown JOB.
Replay ReadReplay(const std::filesystem::path& dir, std::optional<int> job, int max_frames = 10000);

// Every job of results folder DIR, in job order, each as ReadReplay(DIR, job, MAX_FRAMES) reads
// it, from one pass over cycles.csv. Throws as ReadReplay does (but never for several jobs).
std::vector<Replay> ReadReplays(const std::filesystem::path& dir, int max_frames = 10000);

// SceneViewData of the replay's scene at its first frame, plus
// "replay": {"experiment", "job", "label", "moving": 0|1, "stride", "models": [{"name",
// "cycles", "t": f32, "pose": f32, "force": f32, "torque": f32, "level": i32, "contacts": i32,
// and for deformable bodies "r", "q": f32, "r_B", "q_B": f32, and for a model that keeps a
// contact surface "surface": {"frames": i32 (#S frame indices, ascending), "start": u32 (#S + 1,
// each frame's first triangle), "corners": f32 (world), "pressure": f32, "pmax",
// "max_triangles"}}]} (no scene-page "surfaces"). A deformable body whose
// coordinates were recorded also gets "modes": r and "basis": f32 (#V x 3 x r), the reduced
// basis at its mesh vertices (u = U q, sec. 4.1), so the page deforms its mesh per frame;
// bodies with more than 16 million basis entries are shown at rest ("basis_omitted": true).
nlohmann::json ReplayViewData(const Replay& replay, SceneAssets& assets, const SceneViewOptions& options);

// The replay of a many-bodies study (its scene one of many bodies, the tool moving): the
// ManyBodiesViewData of its scene with the tool at the first frame, the reduced basis of each
// deformable body whose coordinates were recorded ("modes", "basis", as ReplayViewData gives
// them), and "replay" as ReplayViewData gives it with "moving" the tool's index and per model
// "bodies_q": [{"body": index, "r", "q": f32 (#F x r)}] (no "r", "q", "r_B", "q_B", no surface).
// Throws Error naming world_bodies.csv for coordinates that do not fit their body.
nlohmann::json WorldReplayViewData(const Replay& replay, const AssetOptions& assets, const SceneViewOptions& options);

// The page data of several jobs of one results folder, JOB_DATA[i] the ReplayViewData of
// REPLAYS[i]: {"title": the experiment, "jobs": [{"job", "label", "title"}], "blobs": [text],
// "job_data": [each job's data with every string of at least 1024 characters replaced by
// {"$blob": N}, N its index in "blobs"]}, so that meshes, pointshells and slices the jobs share
// are embedded once. The page (web/viewer/page_data.js) shows the job of #job=I (default the
// first) and a job selector. Throws Error unless there is one page data per replay, and at least one.
nlohmann::json SeveralJobsViewData(const std::vector<Replay>& replays, std::vector<nlohmann::json> job_data);

}  // namespace contactlab
