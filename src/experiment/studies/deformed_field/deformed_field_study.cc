// The deformed-field study (deformed_field_study.h): one job poses the field body,
// builds the exact reference for that pose and measures the proxy field against it; the study
// runs the jobs and writes field_error.csv, field_slice.csv and meta.json.
#include "experiment/studies/deformed_field/deformed_field_study.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <limits>

#include "experiment/csv_line.h"
#include "experiment/result_table.h"
#include "experiment/run_metadata.h"
#include "experiment/study.h"
#include "scene/scene_assets.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

using Clock = std::chrono::steady_clock;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

Eigen::Vector3d Vector3(const ConfigNode& n) {
  const std::vector<double> v = n.AsDoubles();
  if (v.size() != 3) n.Fail("needs 3 numbers x, y, z");
  for (double x : v) {
    if (!std::isfinite(x)) n.Fail("must be finite");
  }
  return {v[0], v[1], v[2]};
}

// Mean nanoseconds of one Distance over the band points POINTS (3 floats each, random order),
// the median over REPEATS passes of about 2e5 queries.
double TimeQueries(const DeformedDistanceField& field, const DeformedFieldState& state, const std::vector<float>& points,
                   int repeats) {
  const std::size_t n = points.size() / 3;
  const int rounds = int(std::max<std::size_t>(1, 200000 / n));
  std::vector<double> ns;
  volatile float sink = 0;
  for (int pass = 0; pass < repeats; ++pass) {
    float sum = 0;
    const auto t0 = Clock::now();
    for (int r = 0; r < rounds; ++r) {
      for (std::size_t i = 0; i < n; ++i) sum += field.Distance(state, &points[3 * i], nullptr);
    }
    const auto t1 = Clock::now();
    sink = sink + sum;
    ns.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / (double(rounds) * double(n)));
  }
  return Median(ns);
}

// Mean nanoseconds of one DeformedFieldState::Update at Q, the median over REPEATS passes.
double TimeUpdate(const DeformedDistanceField& field, DeformedFieldState* state, const Eigen::VectorXd& q,
                  int repeats) {
  constexpr int kRounds = 2000;
  std::vector<double> ns;
  for (int pass = 0; pass < repeats; ++pass) {
    const auto t0 = Clock::now();
    for (int r = 0; r < kRounds; ++r) state->Update(field, q.data());
    ns.push_back(std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / kRounds);
  }
  state->Update(field, q.data());
  return Median(ns);
}

bool SliceWanted(const FieldStudySpec& spec, const Job& job) {
  if (!spec.slice) return false;
  for (const auto& [axis, values] : spec.slice_jobs) {
    bool match = false;
    for (const auto& [a, v] : job.axis_values) {
      match = match || (a == axis && std::find(values.begin(), values.end(), v) != values.end());
    }
    if (!match) return false;
  }
  return true;
}

// Exact and approximate distance on the slice plane, over the rest field's box and the deformed
// surface's bounds (grown by the band), RESOLUTION points along the longer side.
std::vector<FieldSliceRow> Slice(const FieldStudySpec& spec, const DeformedDistanceField& field,
                                 const DeformedFieldState& state, const MeshSignedDistance& exact, double band) {
  Aabb box = field.rest_field().box();
  const Aabb deformed = exact.mesh().Bounds();
  box.min = box.min.cwiseMin(deformed.min - Eigen::Vector3d::Constant(band));
  box.max = box.max.cwiseMax(deformed.max + Eigen::Vector3d::Constant(band));
  const int a = spec.slice_axis, b = a == 0 ? 1 : 0, c = 3 - a - b;  // the plane's axes b < c
  if (spec.slice_window) {
    box.min[b] = spec.window[0], box.min[c] = spec.window[1];
    box.max[b] = spec.window[2], box.max[c] = spec.window[3];
  }
  const double eb = box.max[b] - box.min[b], ec = box.max[c] - box.min[c];
  const double step = std::max(eb, ec) / (spec.slice_resolution - 1);
  const int nb = int(std::round(eb / step)) + 1, nc = int(std::round(ec / step)) + 1;
  std::vector<FieldSliceRow> rows(std::size_t(nb) * nc);
  tbb::parallel_for(0, nc, [&](int j) {
    for (int i = 0; i < nb; ++i) {
      FieldSliceRow& r = rows[std::size_t(j) * nb + i];
      r.i = i;
      r.j = j;
      r.x[a] = spec.slice_at;
      r.x[b] = box.min[b] + i * step;
      r.x[c] = box.min[c] + j * step;
      r.exact = exact.Distance(r.x);
      r.approx = field.Distance(state, r.x);
    }
  });
  return rows;
}

// field_error.csv's declared columns (after experiment, job and the sweep axes not named here).
const TableColumn<FieldErrorRow> kErrorColumns[] = {
    {"proxies", "", "proxies of the deformed distance field",
     [](const FieldErrorRow& r, CsvLine& l) { l.Int(r.proxies); }},
    {"neighbours", "", "k, the nearest proxies blended per query",
     [](const FieldErrorRow& r, CsvLine& l) { l.Int(r.neighbours); }},
    {"domains", "", "domains combined by minimum",
     [](const FieldErrorRow& r, CsvLine& l) { l.Int(r.domains); }},
    {"domain_kind", "", "how the domains were made: regions (given planes or boxes) or auto (clusters)",
     [](const FieldErrorRow& r, CsvLine& l) { l.Text(r.explicit_domains ? "regions" : "auto"); }},
    {"slots", "", "proxy slots over all domains",
     [](const FieldErrorRow& r, CsvLine& l) { l.Int(r.slots); }},
    {"r", "", "reduced coordinates of the field body",
     [](const FieldErrorRow& r, CsvLine& l) { l.Int(r.r); }},
    {"cell_m", "m", "the rest field's grid spacing",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.6g", r.cell); }},
    {"body_size_m", "m", "largest side of the rest mesh's bounding box",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.6g", r.body_size); }},
    {"max_displacement_m", "m", "largest surface displacement of the pose",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.6g", r.max_displacement); }},
    {"points", "", "band points measured",
     [](const FieldErrorRow& r, CsvLine& l) { l.Int(r.points); }},
    {"rms_cells", "", "RMS of approximate - exact distance in the contact band, in cells of cell_m",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.5g", r.rms / r.cell); }},
    {"max_cells", "", "largest |approximate - exact| in the band, in cells",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.5g", r.max / r.cell); }},
    {"mean_cells", "", "mean approximate - exact in the band, in cells",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.5g", r.mean / r.cell); }},
    {"rms_m", "m", "RMS of approximate - exact distance in the band",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.6g", r.rms); }},
    {"max_m", "m", "largest |approximate - exact| in the band",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.6g", r.max); }},
    {"false_inside_m3", "m^3", "volume the approximate field calls inside and the exact one outside (mirroring)",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.6g", r.false_inside_volume); }},
    {"query_ns", "ns", "one deformed-field distance query, median over the timing passes",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.2f", r.query_ns); }},
    {"update_ns", "ns", "one update of the field's state to a new q",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.1f", r.update_ns); }},
    {"exact_ns", "ns", "one exact reference distance (BVH and pseudo-normal)",
     [](const FieldErrorRow& r, CsvLine& l) { l.Num("%.1f", r.exact_ns); }},
};

// field_slice.csv's declared columns (after experiment, job and every sweep axis).
const TableColumn<FieldSliceRow> kSliceColumns[] = {
    {"i", "", "grid index along the plane's first axis", [](const FieldSliceRow& r, CsvLine& l) { l.Int(r.i); }},
    {"j", "", "grid index along the plane's second axis", [](const FieldSliceRow& r, CsvLine& l) { l.Int(r.j); }},
    {"x", "m", "the grid point, body frame, x", [](const FieldSliceRow& r, CsvLine& l) { l.Num("%.7g", r.x[0]); }},
    {"y", "m", "the grid point, body frame, y", [](const FieldSliceRow& r, CsvLine& l) { l.Num("%.7g", r.x[1]); }},
    {"z", "m", "the grid point, body frame, z", [](const FieldSliceRow& r, CsvLine& l) { l.Num("%.7g", r.x[2]); }},
    {"exact_m", "m", "exact signed distance to the deformed surface",
     [](const FieldSliceRow& r, CsvLine& l) { l.Num("%.7g", r.exact); }},
    {"approx_m", "m", "the deformed distance field's distance",
     [](const FieldSliceRow& r, CsvLine& l) { l.Num("%.7g", r.approx); }},
};

const ResultTable& ErrorTable() {
  static const ResultTable table =
      DeclareTable("field_error.csv", "one row per job", TableKeys::kJobAndOtherAxes, kErrorColumns);
  return table;
}
const ResultTable& SliceTable() {
  static const ResultTable table = DeclareTable("field_slice.csv", "one row per slice grid point of a job that writes it",
                                                TableKeys::kJobAndAllAxes, kSliceColumns);
  return table;
}

std::string ErrorCsv(const ExperimentConfig& config, const std::vector<FieldJobResult>& results) {
  const ResultTable& table = ErrorTable();
  std::string out = table.Header(config);
  for (const FieldJobResult& r : results) {
    CsvLine line(&out);
    table.AppendKeys(config, r.job, &line);
    AppendCells(kErrorColumns, r.error, &line);
    out += '\n';
  }
  return out;
}

std::string SliceCsv(const ExperimentConfig& config, const std::vector<FieldJobResult>& results) {
  const ResultTable& table = SliceTable();
  std::string out = table.Header(config);
  for (const FieldJobResult& r : results) {
    for (const FieldSliceRow& row : r.slice) {
      CsvLine line(&out);
      table.AppendKeys(config, r.job, &line);
      AppendCells(kSliceColumns, row, &line);
      out += '\n';
    }
  }
  return out;
}

}  // namespace

FieldStudySpec ParseFieldStudySpec(const ConfigNode& root) {
  FieldStudySpec s;
  if (!root.Has("deformation")) root.Fail("a deformed-field study needs a 'deformation' section (loads, max_displacement)");
  const ConfigNode d = root.Get("deformation");
  d.ExpectKeys({"loads", "max_displacement"});
  const ConfigNode loads = d.Get("loads");
  for (const ConfigNode& l : loads.Elements()) {
    l.ExpectKeys({"at", "force"});
    PointLoad load;
    load.at = Vector3(l.Get("at"));
    load.force = Vector3(l.Get("force"));
    if (!(load.force.norm() > 0)) l.Get("force").Fail("must not be zero");
    s.loads.push_back(load);
    s.load_where.push_back(l.Get("at").Location());
  }
  if (s.loads.empty()) loads.Fail("needs at least one load {at: [x, y, z], force: [fx, fy, fz]}");
  s.max_displacement = d.Positive("max_displacement", s.max_displacement);
  if (s.max_displacement > 1) d.Get("max_displacement").Fail("is a fraction of the body's size: at most 1");
  if (auto m = root.Find("measure")) {
    m->ExpectKeys({"band_cells", "points", "seed", "timing_repeats", "slice"});
    s.band_cells = m->Positive("band_cells", s.band_cells);
    s.points = int(m->IntInRange("points", s.points, 10, 10000000));
    s.seed = std::uint64_t(m->IntInRange("seed", 1, 0, std::numeric_limits<std::int32_t>::max()));
    s.timing_repeats = int(m->IntInRange("timing_repeats", s.timing_repeats, 1, 1000));
    if (auto sl = m->Find("slice")) {
      sl->ExpectKeys({"axis", "at", "resolution", "window", "jobs"});
      s.slice = true;
      const std::string axis = sl->OneOf("axis", "z", {"x", "y", "z"});
      s.slice_axis = axis == "x" ? 0 : axis == "y" ? 1 : 2;
      s.slice_at = sl->Double("at", 0);
      if (!std::isfinite(s.slice_at)) sl->Get("at").Fail("must be finite");
      s.slice_resolution = int(sl->IntInRange("resolution", s.slice_resolution, 8, 4000));
      if (auto w = sl->Find("window")) {
        const std::vector<double> v = w->AsDoubles();
        if (v.size() != 4) w->Fail("needs 4 numbers: the low and high corners on the plane's two axes, metres");
        if (!(v[0] < v[2] && v[1] < v[3])) w->Fail("the low corner must be below the high corner on both axes");
        for (double x : v) {
          if (!std::isfinite(x)) w->Fail("must be finite");
        }
        s.slice_window = true;
        s.window = Eigen::Vector4d(v[0], v[1], v[2], v[3]);
      }
      if (auto j = sl->Find("jobs")) {
        j->ExpectMap();
        for (const std::string& key : j->Keys()) {
          const ConfigNode v = j->Get(key);
          std::vector<std::string> values;
          for (const ConfigNode& e : v.IsSequence() ? v.Elements() : std::vector<ConfigNode>{v}) {
            if (!e.IsScalar()) e.Fail("must be a sweep value (or label) or a list of them");
            values.push_back(e.AsString());
          }
          if (values.empty()) v.Fail("lists no value");
          s.slice_jobs.emplace_back(key, values);
        }
      }
    }
  }
  return s;
}

FieldJobResult RunDeformedFieldJob(const ExperimentConfig& config, const Job& job, const RunOptions& options) {
  const FieldStudySpec spec = ParseFieldStudySpec(job.config);
  const std::string where = config.file + ": job " + std::to_string(job.index) + " (" + job.Label() + ")";
  const BodySpec& body = job.scene.field_body;
  if (!body.deformable) {
    Fail(where, "the scene's field body '" + body.name + "' is rigid; a deformed-field study needs a deformable block");
  }
  SceneAssets assets(job.scene, options.assets);
  BodyAssets& B = assets.B;
  const auto mesh = B.mesh();
  const auto rest = B.field();
  const auto model = B.reduced_model();
  const auto field = B.deformed_field();
  const double h = rest->spacing();
  const double size = mesh->Bounds().size().maxCoeff();

  // The pose: the loads act at material points of the body, scaled to the target displacement.
  for (std::size_t i = 0; i < spec.loads.size(); ++i) {
    const double d = rest->Distance(spec.loads[i].at);
    if (d > 2 * h) {
      Fail(spec.load_where[i], "the point lies " + std::to_string(d) + " m outside body '" + body.name +
                                   "' (loads act at material points of the body, body frame, metres)");
    }
  }
  const EmbeddedSurface surface(*mesh, model->mesh, model->basis);
  const Eigen::VectorXd q = SolveScaledPointLoadPose(model->forces, model->mesh, model->basis, spec.loads, surface,
                                                     spec.max_displacement * size, where);
  const MeshSignedDistance exact(surface.Deformed(q), where + ": the deformed surface of '" + body.name + "'");
  DeformedFieldState state(*field);
  state.Update(*field, q.data());

  // Errors in the contact band, then the cost of a query and of an update.
  BandErrorOptions bo;
  bo.band = spec.band_cells * h;
  bo.points = spec.points;
  bo.seed = spec.seed;
  const BandError e = MeasureBandError(*field, state, exact, bo, where);
  FieldJobResult result;
  result.job = job;
  FieldErrorRow& row = result.error;
  row.proxies = field->num_proxies();
  row.neighbours = field->neighbours();
  row.domains = field->num_domains();
  row.explicit_domains = !body.deformable->field.regions.empty();
  row.slots = field->num_slots();
  row.r = field->r();
  row.cell = h;
  row.body_size = size;
  row.max_displacement = surface.MaxDisplacement(q);
  row.points = e.points;
  row.rms = e.rms;
  row.max = e.max;
  row.mean = e.mean;
  row.false_inside_volume = e.false_inside_volume;
  row.query_ns = TimeQueries(*field, state, e.band_points, spec.timing_repeats);
  row.update_ns = TimeUpdate(*field, &state, q, spec.timing_repeats);
  {
    const auto t0 = Clock::now();
    double sink = 0;
    for (std::size_t i = 0; i < e.exact.size(); ++i) {
      sink += exact.Distance(Eigen::Map<const Eigen::Vector3f>(&e.band_points[3 * i]).cast<double>());
    }
    row.exact_ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / double(e.exact.size());
    if (!std::isfinite(sink)) Fail(where, "the exact distance is not finite");
  }
  if (SliceWanted(spec, job)) result.slice = Slice(spec, *field, state, exact, bo.band);
  return result;
}

std::vector<FieldErrorRow> RunDeformedFieldStudy(const ExperimentConfig& config, const RunOptions& options,
                                                 const std::vector<int>& job_indices) {
  std::vector<FieldJobResult> results(job_indices.empty() ? JobCount(config) : job_indices.size());
  const JobsRun jobs = RunJobs(config, job_indices, options, [&](std::size_t i, const Job& job) {
    results[i] = RunDeformedFieldJob(config, job, options);
  });
  WriteStudyResults(StudyOf(config), options.out_dir, {ErrorCsv(config, results), SliceCsv(config, results)},
                    RunMetadata(config, jobs.indices, jobs.wall_seconds, jobs.parallel));
  std::vector<FieldErrorRow> rows;
  for (const FieldJobResult& r : results) rows.push_back(r.error);
  return rows;
}

namespace {

// The job's sections parse, its field body is deformable, and the slice's job filter names
// sweep axes and their values.
void CheckFieldStudy(const ExperimentConfig& c, const ConfigNode& root, const Job& job) {
  const FieldStudySpec spec = ParseFieldStudySpec(job.config);
  if (!job.scene.field_body.deformable) {
    Fail(c.file, "study: deformed-field needs a deformable field body, but body '" + job.scene.field_body.name +
                     "' of " + job.scene.file + (c.sweep.empty() ? "" : " (job " + job.Label() + ")") +
                     " has no deformable block");
  }
  for (const auto& [axis, values] : spec.slice_jobs) {
    const ConfigNode where = root.Get("measure").Get("slice").Get("jobs").Get(axis);
    const std::string& name = axis;  // a structured binding cannot be captured by clang 14
    const auto a = std::find_if(c.sweep.begin(), c.sweep.end(), [&name](const SweepAxis& s) { return s.name == name; });
    if (a == c.sweep.end()) where.Fail("is not a sweep axis of this config");
    for (const std::string& v : values) {
      if (std::find(a->values.begin(), a->values.end(), v) == a->values.end()) {
        where.Fail("'" + v + "' is not a value (or label) of sweep." + axis);
      }
    }
  }
}

// Runs the jobs and prints the error table.
void RunFieldStudy(const ExperimentConfig& config, const RunOptions& options, const std::vector<int>& only) {
  const std::size_t total = JobCount(config);
  std::fprintf(stderr, "experiment %s (deformed-field study): %zu of %zu jobs\n", config.name.c_str(),
               only.empty() ? total : only.size(), total);
  const std::vector<FieldErrorRow> rows = RunDeformedFieldStudy(config, options, only);
  std::printf("%-8s %-10s %-8s %10s %10s %11s %10s\n", "proxies", "neighbours", "domains", "rms cells", "max cells",
              "false cm^3", "query ns");
  for (const FieldErrorRow& r : rows) {
    std::printf("%-8d %-10d %-8d %10.3f %10.3f %11.4g %10.1f\n", r.proxies, r.neighbours, r.domains, r.rms / r.cell,
                r.max / r.cell, r.false_inside_volume * 1e6, r.query_ns);
  }
}

}  // namespace

void RegisterDeformedFieldStudy() {
  Study s;
  s.name = "deformed-field";
  s.description = "the field body's deformed distance field against the exact distance (sec. 4.2, Fig. 10)";
  s.sections = {
      {"deformation", "mapping: loads, max_displacement (required)", "how the field body is deformed in each job"},
      {"measure", "mapping: points, slice", "where the deformed field is compared with the exact distance"},
  };
  s.required = {"deformation"};
  s.aliases = {{"max_displacement", "deformation.max_displacement"}};
  s.tables = {ErrorTable(), SliceTable()};
  s.timing = true;  // it measures query times: one job at a time
  s.check = CheckFieldStudy;
  s.run = RunFieldStudy;
  RegisterStudy(std::move(s));
}

}  // namespace contactlab
