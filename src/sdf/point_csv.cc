// CSV points and distances for sdf-eval (Barbič & James 2008, sec. 2.3).
#include "sdf/point_csv.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>

#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool ParseNumber(const std::string& field, double* value) {
  const std::string t = Trim(field);
  if (t.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && errno != ERANGE;
}

}  // namespace

std::vector<Eigen::Vector3d> ReadPointsCsv(const std::filesystem::path& path) {
  const std::string text = ReadWholeFile(path);
  std::vector<Eigen::Vector3d> points;
  std::istringstream in(text);
  std::string line;
  long number = 0;
  bool first_content = true;
  while (std::getline(in, line)) {
    ++number;
    if (Trim(line).empty()) continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    std::string f;
    while (std::getline(ss, f, ',')) fields.push_back(f);
    if (!line.empty() && line.back() == ',') fields.push_back("");
    double first = 0;
    if (first_content && !fields.empty() && !ParseNumber(fields[0], &first)) {
      first_content = false;  // header line
      continue;
    }
    first_content = false;
    if (fields.size() != 3) {
      FailAtLine(path.string(), number, "expected 3 fields x,y,z, found " + std::to_string(fields.size()));
    }
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) {
      if (!ParseNumber(fields[a], &p[a]) || !std::isfinite(p[a])) {
        FailAtLine(path.string(), number, "field " + std::to_string(a + 1) + " ('" + Trim(fields[a]) +
                                              "') is not a finite number");
      }
    }
    points.push_back(p);
  }
  return points;
}

void WritePointDistancesCsv(const std::filesystem::path& path, const std::vector<Eigen::Vector3d>& points,
                            const std::vector<double>& distances) {
  if (points.size() != distances.size()) Fail(path.string(), "points and distances differ in number");
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "x,y,z,d\n";
    char buf[128];
    for (std::size_t n = 0; n < points.size(); ++n) {
      std::snprintf(buf, sizeof(buf), "%.17g,%.17g,%.17g,%.9g\n", points[n].x(), points[n].y(), points[n].z(),
                    distances[n]);
      out << buf;
    }
  });
}

}  // namespace contactlab
