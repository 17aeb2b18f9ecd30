#include "view/module_bundle.h"

#include <cctype>
#include <map>
#include <regex>
#include <sstream>

#include "util/error.h"

namespace contactlab {
namespace {

// "MODULE:LINE" for error messages.
std::string Where(const std::string& module, int line) { return module + ":" + std::to_string(line); }

// The identifier of module NAME's exports in the bundle: "module_" and NAME with every
// character other than a letter or digit as '_', e.g. module_viewer_main_js.
std::string ExportsName(const std::string& name) {
  std::string id = "module_";
  for (char c : name) id += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return id;
}

// Module NAME's folder ("" at the top), with its '/'.
std::string FolderOf(const std::string& name) {
  const std::size_t slash = name.rfind('/');
  return slash == std::string::npos ? "" : name.substr(0, slash + 1);
}

// One module parsed: its lines rewritten for the bundle, the modules it imports (in order) and
// the names it exports.
struct ParsedModule {
  std::vector<std::string> lines;
  std::vector<std::string> imports;
  std::vector<std::string> exports;
};

// Module NAME's import line TEXT (line LINE) as a destructuring of the imported module's
// exports; adds that module to *IMPORTS.
std::string RewriteImport(const std::string& name, int line, const std::string& text,
                          std::vector<std::string>* imports) {
  static const std::regex kImport(R"(^import \{([\w$, ]*)\} from '\./([\w.-]+\.js)';\s*$)");
  std::smatch m;
  if (!std::regex_match(text, m, kImport)) {
    Fail(Where(name, line), "an import the bundle does not handle (expected import { a, b as c } from './name.js';)");
  }
  const std::string from = FolderOf(name) + m[2].str();
  imports->push_back(from);
  // `a as b` is `a: b` in a destructuring.
  const std::string bindings = std::regex_replace(m[1].str(), std::regex(R"(\s+as\s+)"), ": ");
  return "const {" + bindings + "} = " + ExportsName(from) + ";";
}

// Module NAME's export line TEXT (line LINE) without `export`; adds the name to *EXPORTS.
std::string RewriteExport(const std::string& name, int line, const std::string& text,
                          std::vector<std::string>* exports) {
  static const std::regex kExport(R"(^export ((?:async )?function\*? ?|class |const )([A-Za-z_$][\w$]*))");
  std::smatch m;
  if (!std::regex_search(text, m, kExport)) {
    Fail(Where(name, line), "an export the bundle does not handle (expected export function|class|const NAME)");
  }
  exports->push_back(m[2].str());
  return text.substr(std::string_view("export ").size());
}

ParsedModule Parse(const std::string& name, std::string_view source) {
  ParsedModule parsed;
  std::istringstream in{std::string(source)};
  int line = 0;
  for (std::string text; std::getline(in, text);) {
    ++line;
    if (text.rfind("import ", 0) == 0 || text.rfind("import{", 0) == 0) {
      parsed.lines.push_back(RewriteImport(name, line, text, &parsed.imports));
    } else if (text.rfind("export ", 0) == 0 || text.rfind("export{", 0) == 0) {
      parsed.lines.push_back(RewriteExport(name, line, text, &parsed.exports));
    } else {
      parsed.lines.push_back(text);
    }
  }
  return parsed;
}

// Depth-first over the imports: appends NAME to *ORDER after the modules it imports.
struct Orderer {
  const std::map<std::string, std::string_view>& sources;
  std::map<std::string, ParsedModule> parsed;
  std::vector<std::string> order;
  std::vector<std::string> path;  // the modules being visited, outermost first

  void Visit(const std::string& name, const std::string& importer) {
    if (parsed.count(name)) return;
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (path[i] != name) continue;
      std::string cycle;
      for (std::size_t k = i; k < path.size(); ++k) cycle += path[k] + " -> ";
      Fail(name, "is in an import cycle: " + cycle + name);
    }
    const auto source = sources.find(name);
    if (source == sources.end()) Fail(importer.empty() ? name : importer, "imports " + name + ", which is not among the modules");
    path.push_back(name);
    ParsedModule module = Parse(name, source->second);
    for (const std::string& import : module.imports) Visit(import, name);
    path.pop_back();
    parsed.emplace(name, std::move(module));
    order.push_back(name);
  }
};

}  // namespace

std::string BundleModules(const std::vector<JsModule>& modules, std::string_view entry) {
  std::map<std::string, std::string_view> sources;
  for (const JsModule& m : modules) sources.emplace(m.name, m.source);
  Orderer orderer{sources, {}, {}, {}};
  orderer.Visit(std::string(entry), "");
  // Each module a function run once, after those it imports, returning its exports.
  std::string out = "// The viewer's modules, bundled (src/view/module_bundle.h): each one's exports, in the order\n"
                    "// they run.\n";
  for (const std::string& name : orderer.order) {
    const ParsedModule& m = orderer.parsed.at(name);
    out += "\n// --- " + name + "\nconst " + ExportsName(name) + " = (() => {\n";
    for (const std::string& line : m.lines) out += line + "\n";
    out += "return {";
    for (std::size_t i = 0; i < m.exports.size(); ++i) out += (i ? ", " : "") + m.exports[i];
    out += "};\n})();\n";
  }
  return out;
}

}  // namespace contactlab
