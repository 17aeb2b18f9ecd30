// CSV points and distances for sdf-eval (Barbič & James 2008, sec. 2.3).
#include "sdf/point_csv.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <string_view>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/number_text.h"

namespace contactlab {
namespace {

std::string Trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r");
  return s.substr(b, e - b + 1);
}

bool ParseNumber(const std::string& field, double* value) {
  errno = 0;
  const std::string t = Trim(field);
  if (t.empty()) return false;
  char* end = nullptr;
  *value = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size() && errno != ERANGE;
}

// A header cell is a name: it starts with a letter or '_' and holds only letters, digits and
// "_ -.()[]" (e.g. "x", "y_m", "z (m)"). "inf" and "nan" are numbers, not names.
bool IsNameCell(const std::string& field) {
  const std::string t = Trim(field);
  if (t.empty() || !(std::isalpha(static_cast<unsigned char>(t[0])) || t[0] == '_')) return false;
  double ignored = 0;
  if (ParseNumber(t, &ignored) || errno == ERANGE) return false;
  for (const char c : t) {
    const auto u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && std::string_view("_ -.()[]").find(c) == std::string_view::npos) return false;
  }
  return true;
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
    // An optional header, only when every cell is a name: a first row such as "1;2;3",
    // "1 2 3" or "1e400,0,0" is a bad row, not a header to skip silently.
    if (first_content) {
      first_content = false;
      bool header = !fields.empty();
      for (const std::string& cell : fields) header = header && IsNameCell(cell);
      if (header) continue;
    }
    if (fields.size() != 3) {
      FailAtLine(path.string(), number,
                 "expected 3 fields x,y,z (comma-separated), found " + std::to_string(fields.size()) + " in '" +
                     QuoteToken(Trim(line)) + "'");
    }
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) {
      if (!ParseNumber(fields[a], &p[a]) || !std::isfinite(p[a])) {
        const bool out_of_range = errno == ERANGE;
        FailAtLine(path.string(), number,
                   "field " + std::to_string(a + 1) + " ('" + QuoteToken(Trim(fields[a])) + "') is " +
                       (out_of_range ? "out of range (finite doubles only, |x| < 1.8e308)" : "not a finite number"));
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
    std::string text = "x,y,z,d\n";
    for (std::size_t n = 0; n < points.size(); ++n) {
      const std::string row = "row " + std::to_string(n + 2);
      for (int c = 0; c < 3; ++c) {
        AppendNumber(points[n][c], &text, row + " point");
        text += ',';
      }
      AppendNumber(distances[n], &text, row + " distance d");
      text += '\n';
    }
    out << text;
  });
}

}  // namespace contactlab
