#include "experiment/studies/contact/result_csv.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>
#include <utility>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab {
namespace {

// One cell of a table being read: its text, and where it is for the errors.
class CsvCell {
 public:
  CsvCell(std::string_view text, const std::string& file, long line, const char* column)
      : text_(text), file_(file), line_(line), column_(column) {}

  std::string_view text() const { return text_; }
  bool empty() const { return text_.empty(); }
  double Number() const {
    if (text_.empty()) Fail("empty cell, expected a number");
    const std::optional<double> v = ParseDouble(text_);
    if (!v) Fail(QuoteToken(text_) + " is not a number");
    return *v;
  }
  // An integer that fits T.
  template <class T>
  T Integer() const {
    if (text_.empty()) Fail("empty cell, expected an integer");
    const std::optional<long long> v = ParseInteger(text_);
    if (!v) Fail(QuoteToken(text_) + " is not an integer");
    if (*v < std::numeric_limits<T>::min() || *v > std::numeric_limits<T>::max()) {
      Fail(QuoteToken(text_) + " is out of range");
    }
    return T(*v);
  }
  // The number, or FALLBACK for an empty cell (a value the row does not have).
  double NumberOr(double fallback) const { return text_.empty() ? fallback : Number(); }
  // Space-separated numbers (none for an empty cell), into *OUT.
  void Numbers(std::vector<double>* out) const {
    out->clear();
    std::size_t at = 0;
    while (at < text_.size()) {
      const std::size_t begin = text_.find_first_not_of(' ', at);
      if (begin == std::string_view::npos) break;
      const std::size_t end = std::min(text_.find(' ', begin), text_.size());
      const std::string_view item = text_.substr(begin, end - begin);
      const std::optional<double> v = ParseDouble(item);
      if (!v) Fail("number " + std::to_string(out->size() + 1) + ": " + QuoteToken(item) + " is not a number");
      out->push_back(*v);
      at = end;
    }
  }
  [[noreturn]] void Fail(const std::string& what) const {
    FailAtLine(file_, line_, "column " + std::string(column_) + ": " + what);
  }

 private:
  std::string_view text_;
  const std::string& file_;
  long line_;
  const char* column_;
};

// A column of cycles.csv: its name, how a row is written, and how a cell is read back into a
// record (the inverse: an empty cell gives the row without that value).
struct CycleColumn {
  const char* name;
  const char* unit;
  const char* meaning;
  void (*write)(const CycleRow&, CsvLine&);
  void (*read)(const CsvCell&, CyclesCsvRow&);
};

// cycles.csv: the moving body's pose (origin x,y,z and orientation quaternion qw,qx,qy,qz,
// world), the model's wrench on the moving body, its contact statistics and time per cycle,
// and the reference force where one was evaluated (empty cells elsewhere).
const CycleColumn kCycleColumns[] = {
    {"model", "", "the contact model, by its registered name",
     [](const CycleRow& r, CsvLine& l) { l.Text(r.model); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.model = c.text(); }},
    {"cycle", "", "the cycle's index along the trajectory, from 0",
     [](const CycleRow& r, CsvLine& l) { l.Int(r.cycle); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.cycle = c.Integer<std::int64_t>(); }},
    {"t", "s", "the cycle's time from the trajectory's start (cycle times model.cycle_seconds)",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.6f", r.t); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.t = c.Number(); }},
    {"x", "m", "the moving body's origin, world frame, x",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.position.x()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.position.x() = c.Number(); }},
    {"y", "m", "the moving body's origin, world frame, y",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.position.y()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.position.y() = c.Number(); }},
    {"z", "m", "the moving body's origin, world frame, z",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.position.z()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.position.z() = c.Number(); }},
    {"qw", "", "the moving body's orientation, world frame: unit quaternion, w",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.w()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.rotation.w() = c.Number(); }},
    {"qx", "", "the moving body's orientation, world frame: unit quaternion, x",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.x()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.rotation.x() = c.Number(); }},
    {"qy", "", "the moving body's orientation, world frame: unit quaternion, y",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.y()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.rotation.y() = c.Number(); }},
    {"qz", "", "the moving body's orientation, world frame: unit quaternion, z",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.z()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.rotation.z() = c.Number(); }},
    {"fx", "N", "the model's force on the moving body, world frame, x",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.force.x()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.force.x() = c.Number(); }},
    {"fy", "N", "the model's force on the moving body, world frame, y",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.force.y()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.force.y() = c.Number(); }},
    {"fz", "N", "the model's force on the moving body, world frame, z",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.force.z()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.force.z() = c.Number(); }},
    {"tx", "N m", "the model's torque on the moving body about its origin, world frame, x",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.torque.x()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.torque.x() = c.Number(); }},
    {"ty", "N m", "the model's torque on the moving body about its origin, world frame, y",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.torque.y()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.torque.y() = c.Number(); }},
    {"tz", "N m", "the model's torque on the moving body about its origin, world frame, z",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.torque.z()); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.torque.z() = c.Number(); }},
    {"contacts", "", "points (or pairs) in contact",
     [](const CycleRow& r, CsvLine& l) { l.Int(r.contacts); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.contacts = c.Integer<int>(); }},
    {"nodes", "", "tree nodes the traversal visited",
     [](const CycleRow& r, CsvLine& l) { l.Int(r.nodes); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.nodes = c.Integer<std::int64_t>(); }},
    {"level", "", "deepest tree level rendered (empty: the model walks no tree)",
     [](const CycleRow& r, CsvLine& l) { r.level >= 0 ? l.Int(r.level) : l.Empty(); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.level = c.empty() ? -1 : c.Integer<int>(); }},
    {"max_penetration", "m", "largest penetration depth",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.6g", r.max_penetration); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.max_penetration = c.Number(); }},
    {"depth_voxels", "", "max_penetration in cells of the field body's grid (models that read it; 0 otherwise)",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.4g", r.depth_voxels); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.depth_voxels = c.Number(); }},
    {"contact_area", "m^2", "area of the contact surface (models with one, e.g. pressure-field; 0 otherwise)",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.6g", r.contact_area); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.contact_area = c.NumberOr(0); }},
    {"patches", "", "connected pieces of the contact surface",
     [](const CycleRow& r, CsvLine& l) { l.Int(r.patches); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.patches = c.empty() ? 0 : c.Integer<int>(); }},
    {"degraded", "", "steps the model degraded under the scene's node_budget, in its own unit (0: it did all its work)",
     [](const CycleRow& r, CsvLine& l) { l.Int(r.degraded); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.degraded = c.empty() ? 0 : c.Integer<int>(); }},
    {"time_us", "us", "the model's contact query, wall time",
     [](const CycleRow& r, CsvLine& l) { l.Num("%.3f", r.time_us); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.time_us = c.Number(); }},
    {"ref_fx", "N", "the reference model's force on the moving body, world frame, x (empty: not evaluated this cycle)",
     [](const CycleRow& r, CsvLine& l) { r.has_reference ? l.Num("%.9g", r.reference_force.x()) : l.Empty(); },
     [](const CsvCell& c, CyclesCsvRow& r) {
       r.values.has_reference = !c.empty();
       r.values.reference_force.x() = c.NumberOr(0);
     }},
    {"ref_fy", "N", "the reference model's force on the moving body, world frame, y (empty: not evaluated this cycle)",
     [](const CycleRow& r, CsvLine& l) { r.has_reference ? l.Num("%.9g", r.reference_force.y()) : l.Empty(); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.reference_force.y() = c.NumberOr(0); }},
    {"ref_fz", "N", "the reference model's force on the moving body, world frame, z (empty: not evaluated this cycle)",
     [](const CycleRow& r, CsvLine& l) { r.has_reference ? l.Num("%.9g", r.reference_force.z()) : l.Empty(); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.reference_force.z() = c.NumberOr(0); }},
    {"step_us", "us", "body A's reduced integrator step after the query, wall time (empty: A rigid)",
     [](const CycleRow& r, CsvLine& l) { r.q.empty() ? l.Empty() : l.Num("%.3f", r.step_us); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.step_us = c.NumberOr(0); }},
    {"step_B_us", "us", "body B's reduced integrator step after the query, wall time (empty: B rigid)",
     [](const CycleRow& r, CsvLine& l) { r.q_B.empty() ? l.Empty() : l.Num("%.3f", r.step_B_us); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.step_B_us = c.NumberOr(0); }},
    {"elastic_energy_J", "J", "elastic energy of both bodies after the cycle's steps (empty: both rigid)",
     [](const CycleRow& r, CsvLine& l) { r.deformable ? l.Num("%.9g", r.elastic_energy) : l.Empty(); },
     [](const CsvCell& c, CyclesCsvRow& r) {
       r.values.deformable = !c.empty();
       r.values.elastic_energy = c.NumberOr(0);
     }},
    {"kinetic_energy_J", "J", "kinetic energy of both bodies after the cycle's steps (empty: both rigid)",
     [](const CycleRow& r, CsvLine& l) { r.deformable ? l.Num("%.9g", r.kinetic_energy) : l.Empty(); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.kinetic_energy = c.NumberOr(0); }},
    {"max_displacement", "m", "largest |U q| over the simulation meshes' vertices after the steps (empty: both rigid)",
     [](const CycleRow& r, CsvLine& l) { r.deformable ? l.Num("%.9g", r.max_displacement) : l.Empty(); },
     [](const CsvCell& c, CyclesCsvRow& r) { r.values.max_displacement = c.NumberOr(0); }},
    {"q", "", "body A's reduced coordinates q_1 .. q_r after the step, space-separated (mass-normalised; empty: A rigid)",
     [](const CycleRow& r, CsvLine& l) { l.Numbers("%.9g", r.q); },
     [](const CsvCell& c, CyclesCsvRow& r) { c.Numbers(&r.q); }},
    {"q_B", "", "body B's reduced coordinates after the step, space-separated (empty: B rigid)",
     [](const CycleRow& r, CsvLine& l) { l.Numbers("%.9g", r.q_B); },
     [](const CsvCell& c, CyclesCsvRow& r) { c.Numbers(&r.q_B); }},
};

// summary.csv: per model and job, continuity, timing, error against the reference and force
// magnitude metrics, and the memory of the body data the model reads. A cell with no value (no
// reference, no pointshell read, a rigid body) is empty, as in every table.
const TableColumn<SummaryRow> kSummaryColumns[] = {
    {"model", "", "the contact model, by its registered name",
     [](const SummaryRow& r, CsvLine& l) { l.Text(r.model); }},
    {"points", "", "pointshell points of body A the model reads (the scene's pointshell.points; empty: it reads none)",
     [](const SummaryRow& r, CsvLine& l) { r.reads_pointshell() ? l.Int(r.points) : l.Empty(); }},
    {"cycles", "", "cycles of the trajectory",
     [](const SummaryRow& r, CsvLine& l) { l.Int(r.cycles); }},
    {"max_jump_N", "N", "largest |F(k+1) - F(k)| over consecutive cycles",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.max_jump); }},
    {"lipschitz_N_per_m", "N/m", "largest |dF| / (|dp| + radius |dtheta|) over the cycles that move",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.lipschitz); }},
    {"hf_share", "", "share of the mean-removed force energy above the config's cutoff frequency",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.hf_share); }},
    {"max_jump_rel", "", "max_jump_N over the median |F| in contact (0: no force)",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.max_jump_rel); }},
    {"lipschitz_rel_per_m", "1/m", "lipschitz_N_per_m over the median |F| in contact (0: no force)",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.lipschitz_rel); }},
    {"median_us", "us", "median contact query time",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.median_us); }},
    {"p99_us", "us", "99th percentile of the contact query time",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.p99_us); }},
    {"max_us", "us", "largest contact query time",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.max_us); }},
    {"mean_nodes", "", "tree nodes visited per cycle, mean",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.1f", r.mean_nodes); }},
    {"level_switches_per_s", "1/s", "changes of the rendered tree level per second",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.level_switches_per_s); }},
    {"degraded_share", "", "share of the cycles in which the node budget made the model degrade",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.4g", r.degraded_share); }},
    {"rms_rel_error", "", "RMS force error against the reference over RMS reference force (empty: no reference)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.6g", r.rms_rel_error); }},
    {"max_dir_error_deg", "deg", "largest angle between the force and the reference force (empty: no reference)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.4g", r.max_dir_error_deg); }},
    {"median_dir_error_deg", "deg", "median angle between the force and the reference force (empty: no reference)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.4g", r.median_dir_error_deg); }},
    {"p95_dir_error_deg", "deg", "95th percentile of that angle (empty: no reference)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.4g", r.p95_dir_error_deg); }},
    {"wrench_scale", "", "the factor model.stiffness: matched applied to the model's wrench to match the paper's model's stiffness (1: its own stiffness)",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.wrench_scale); }},
    {"ref_scale", "", "the stiffness scale fitted to the reference force (empty: no reference or no force)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.6g", r.ref_scale); }},
    {"rms_rel_error_calibrated", "", "rms_rel_error after ref_scale (empty: no reference or no force)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.6g", r.rms_rel_error_calibrated); }},
    {"max_force_N", "N", "largest |F| on the moving body",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.max_force); }},
    {"mean_force_N", "N", "mean |F| on the moving body over all cycles",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.mean_force); }},
    {"max_depth_voxels", "", "largest depth_voxels of the trajectory",
     [](const SummaryRow& r, CsvLine& l) { l.Num("%.4g", r.max_depth_voxels); }},
    {"coherence_resets", "", "cycles where the moving body outran model.max_point_speed, each resetting the model",
     [](const SummaryRow& r, CsvLine& l) { l.Int(r.coherence_resets); }},
    {"contact_faults", "", "cycles whose query the model refused (no force)",
     [](const SummaryRow& r, CsvLine& l) { l.Int(r.contact_faults); }},
    {"modes", "", "r of a deformable pointshell body A (0: rigid)",
     [](const SummaryRow& r, CsvLine& l) { l.Int(r.modes); }},
    {"median_step_us", "us", "body A's reduced integrator step, median (empty: A rigid)",
     [](const SummaryRow& r, CsvLine& l) { r.modes > 0 ? l.Num("%.3f", r.median_step_us) : l.Empty(); }},
    {"modes_B", "", "r of a deformable field body B (0: rigid)",
     [](const SummaryRow& r, CsvLine& l) { l.Int(r.modes_B); }},
    {"median_step_B_us", "us", "body B's reduced integrator step, median (empty: B rigid)",
     [](const SummaryRow& r, CsvLine& l) { r.modes_B > 0 ? l.Num("%.3f", r.median_step_B_us) : l.Empty(); }},
    {"max_displacement", "m", "largest |U q| over the trajectory (empty: both rigid)",
     [](const SummaryRow& r, CsvLine& l) { r.modes + r.modes_B > 0 ? l.Num("%.9g", r.max_displacement) : l.Empty(); }},
    {"field_B_bytes", "bytes", "memory of body B's distance field (empty: the model does not read it)",
     [](const SummaryRow& r, CsvLine& l) { r.field_B_bytes >= 0 ? l.Int(r.field_B_bytes) : l.Empty(); }},
    {"pointshell_A_bytes", "bytes", "memory of body A's pointshell: points, normals, tree (empty: the model does not read it)",
     [](const SummaryRow& r, CsvLine& l) { r.reads_pointshell() ? l.Int(r.pointshell_A_bytes) : l.Empty(); }},
    {"fill_A", "", "fraction of body A's volume the model's filling covers: its inner-sphere packing (empty: it fills none)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.4f", r.fill_A); }},
    {"fill_B", "", "fraction of body B's volume the model's filling covers (empty: it fills none)",
     [](const SummaryRow& r, CsvLine& l) { l.NumOrEmpty("%.4f", r.fill_B); }},
};

}  // namespace

const ResultTable& CyclesTable() {
  static const ResultTable table = DeclareTable("cycles.csv", "one row per cycle per model", TableKeys::kJobAndAllAxes,
                                                kCycleColumns);
  return table;
}
const ResultTable& SummaryTable() {
  static const ResultTable table = DeclareTable("summary.csv", "one row per model per job", TableKeys::kJobAndAllAxes,
                                                kSummaryColumns);
  return table;
}

std::string CyclesCsvHeader(const ExperimentConfig& config) { return CyclesTable().Header(config); }
std::string SummaryCsvHeader(const ExperimentConfig& config) { return SummaryTable().Header(config); }

namespace {

template <class Row, class Col, std::size_t N>
void AppendRows(const ResultTable& table, const ExperimentConfig& config, const JobResult& r,
                const std::vector<Row>& rows, const Col (&columns)[N], std::string* out) {
  for (const Row& row : rows) {
    CsvLine line(out);
    table.AppendKeys(config, r.job, &line);
    AppendCells(columns, row, &line);
    *out += '\n';
  }
}

}  // namespace

void AppendCyclesCsv(const ExperimentConfig& config, const JobResult& r, std::string* out) {
  AppendRows(CyclesTable(), config, r, r.cycles, kCycleColumns, out);
}
void AppendSummaryCsv(const ExperimentConfig& config, const JobResult& r, std::string* out) {
  AppendRows(SummaryTable(), config, r, r.summary, kSummaryColumns, out);
}

CycleRow CyclesCsvRow::row() const {
  CycleRow r = values;
  r.job = job;
  r.model = model;
  r.q = q;
  r.q_B = q_B;
  return r;
}

std::vector<std::string> ReadCyclesCsv(const std::filesystem::path& file,
                                       const std::function<void(const CyclesCsvRow&)>& on_row) {
  const std::string name = file.string();
  const std::string text = ReadWholeFile(file);
  CsvReader scan(text, name);
  std::vector<std::string> header, cells;
  if (!scan.Next(&header)) Fail(name, "is empty");

  // The columns by name: experiment and job at their first occurrence, each declared column at
  // its last (a sweep axis may share a column's name, as the axis "model" does, and comes
  // before the declared columns); every header cell left over is a sweep axis.
  std::vector<bool> claimed(header.size(), false);
  auto find = [&](const std::string& column, bool last) {
    for (std::size_t k = 0; k < header.size(); ++k) {
      const std::size_t c = last ? header.size() - 1 - k : k;
      if (header[c] == column && !claimed[c]) {
        claimed[c] = true;
        return c;
      }
    }
    if (column == "qw" || column == "qx" || column == "qy" || column == "qz") {
      Fail(name, "has no orientation column " + column +
                     " (written by an older contactlab before cycles.csv held qw,qx,qy,qz; run the experiment "
                     "again)");
    }
    Fail(name, "has no column '" + column + "' in its header (line 1)");
  };
  const std::size_t c_experiment = find("experiment", false), c_job = find("job", false);
  constexpr std::size_t kColumns = std::size(kCycleColumns);
  std::size_t c_declared[kColumns];
  for (std::size_t k = 0; k < kColumns; ++k) c_declared[k] = find(kCycleColumns[k].name, true);
  std::vector<std::size_t> c_axes;
  std::vector<std::string> axes;
  for (std::size_t c = 0; c < header.size(); ++c) {
    if (claimed[c]) continue;
    c_axes.push_back(c);
    axes.push_back(header[c]);
  }

  // The rows, each cell read by its column; the reduced coordinates of one job's model keep
  // the length of its first row (the body's r).
  struct FirstRow {
    std::size_t q, q_B;
    long line;
  };
  std::map<std::pair<int, std::string>, FirstRow> first_rows;
  CyclesCsvRow record;
  while (scan.Next(&cells)) {
    const long line = scan.line();
    if (cells.size() != header.size()) {
      FailAtLine(name, line,
                 std::to_string(cells.size()) + " cells, the header (line 1) has " + std::to_string(header.size()));
    }
    record = CyclesCsvRow();
    record.line = line;
    record.experiment = cells[c_experiment];
    record.job = CsvCell(cells[c_job], name, line, "job").Integer<int>();
    for (std::size_t c : c_axes) record.axis_values.push_back(cells[c]);
    for (std::size_t k = 0; k < kColumns; ++k) {
      kCycleColumns[k].read(CsvCell(cells[c_declared[k]], name, line, kCycleColumns[k].name), record);
    }
    const auto first =
        first_rows.try_emplace({record.job, record.model}, FirstRow{record.q.size(), record.q_B.size(), line}).first;
    for (const auto& [column, size, first_size] : {std::tuple{"q", record.q.size(), first->second.q},
                                                   std::tuple{"q_B", record.q_B.size(), first->second.q_B}}) {
      if (size != first_size) {
        FailAtLine(name, line,
                   std::string("column ") + column + ": " + std::to_string(size) + " reduced coordinates, but the " +
                       "first row of job " + std::to_string(record.job) + " model " + record.model + " (line " +
                       std::to_string(first->second.line) + ") holds " + std::to_string(first_size));
      }
    }
    on_row(record);
  }
  return axes;
}

}  // namespace contactlab
