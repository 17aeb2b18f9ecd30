#include "view/viewer_page.h"

#include <cctype>
#include <cstdlib>

#include "util/atomic_file.h"
#include "util/error.h"
#include "view/module_bundle.h"
#include "view/page_encoding.h"
#include "view/web_assets.h"

namespace contactlab {
namespace {

namespace fs = std::filesystem;

// The viewer's modules: the embedded files below this folder; the page runs kEntryModule.
constexpr std::string_view kModuleFolder = "viewer/";
constexpr std::string_view kEntryModule = "viewer/main.js";
constexpr std::string_view kScriptType = "text/javascript; charset=utf-8";

// Reads FILE of three.js, naming it and the package that provides it when it cannot.
std::string ReadThreeJsFile(const fs::path& file) {
  if (!fs::exists(file)) {
    Fail(file.string(), "not found: the viewer reads three.js r111 from here; install Debian's libjs-three "
                        "(scripts/install-deps.sh) or point CONTACTLAB_THREEJS_DIR at a folder holding three.min.js "
                        "and examples/js/controls/OrbitControls.js");
  }
  return ReadWholeFile(file);
}

// three.js's two files, read from ThreeJsDir(): their paths and texts.
struct ThreeJs {
  fs::path three_path, orbit_path;
  std::string three, orbit;
};
ThreeJs ReadThreeJs() {
  const fs::path dir = ThreeJsDir();
  ThreeJs t{dir / "three.min.js", dir / "examples/js/controls/OrbitControls.js", "", ""};
  t.three = ReadThreeJsFile(t.three_path);
  t.orbit = ReadThreeJsFile(t.orbit_path);
  return t;
}

// Replaces PLACEHOLDER, looked for from *CURSOR on, by VALUE and moves *CURSOR past VALUE, so
// the placeholders are filled in the order the template holds them and inserted text (three.js,
// the data) is never searched.
void Substitute(std::string* text, std::size_t* cursor, std::string_view placeholder, std::string_view value) {
  const std::size_t at = text->find(placeholder, *cursor);
  if (at == std::string::npos) Fail("viewer.html", "the page template lacks " + std::string(placeholder) + " in order");
  text->replace(at, placeholder.size(), value);
  *cursor = at + value.size();
}

// JS SOURCE read from WHERE, checked to be safe inside a <script> element.
const std::string& CheckScriptSafe(const std::string& source, const std::string& where) {
  std::string lower(source.size(), ' ');
  for (std::size_t i = 0; i < source.size(); ++i) lower[i] = char(std::tolower((unsigned char)source[i]));
  if (lower.find("</script") != std::string::npos) Fail(where, "contains '</script' and cannot be inlined into the page");
  return source;
}

// TEXT with <, > and & as HTML entities.
std::string EscapeHtml(std::string_view text) {
  std::string escaped;
  for (char c : text) {
    if (c == '<') escaped += "&lt;";
    else if (c == '>') escaped += "&gt;";
    else if (c == '&') escaped += "&amp;";
    else escaped += c;
  }
  return escaped;
}

// The page template with DATA's title, the CSS, THREE_SCRIPTS (the <script> elements of
// three.js and OrbitControls), DATA and VIEWER_SCRIPT (the <script type="module"> of the
// viewer) in place.
std::string FillTemplate(const nlohmann::json& data, std::string_view three_scripts, std::string_view viewer_script) {
  std::string page(EmbeddedWebFile("viewer.html"));
  std::size_t cursor = 0;
  Substitute(&page, &cursor, "@TITLE@", EscapeHtml(data.value("title", std::string("contactlab view"))));
  Substitute(&page, &cursor, "/*@VIEWER_CSS@*/", EmbeddedWebFile("viewer.css"));
  Substitute(&page, &cursor, "<!--@THREE_SCRIPTS@-->", three_scripts);
  Substitute(&page, &cursor, "@DATA@", ScriptSafeJson(data));
  Substitute(&page, &cursor, "<!--@VIEWER_SCRIPT@-->", viewer_script);
  return page;
}

}  // namespace

void RequireThreeJs() {
  const fs::path dir = ThreeJsDir();
  for (const fs::path& file : {dir / "three.min.js", dir / "examples/js/controls/OrbitControls.js"}) {
    if (!fs::is_regular_file(file)) ReadThreeJsFile(file);  // throws naming FILE
  }
}

fs::path ThreeJsDir() {
  if (const char* dir = std::getenv("CONTACTLAB_THREEJS_DIR"); dir != nullptr && *dir != '\0') return dir;
  return CONTACTLAB_THREEJS_DIR;
}

std::string_view EmbeddedWebFile(std::string_view name) {
  for (const web_assets::TextFile& f : web_assets::Files()) {
    if (f.name == name) return f.text;
  }
  Fail("viewer", "no embedded web file " + QuoteToken(name));
}

std::vector<std::string> ViewerModuleNames() {
  std::vector<std::string> names;
  for (const web_assets::TextFile& f : web_assets::Files()) {
    if (f.name.starts_with(kModuleFolder)) names.emplace_back(f.name);
  }
  return names;
}

std::string ViewerPage(const nlohmann::json& data) {
  const ThreeJs three = ReadThreeJs();
  std::vector<JsModule> modules;
  for (const std::string& name : ViewerModuleNames()) modules.push_back({name, EmbeddedWebFile(name)});
  const std::string bundle = BundleModules(modules, kEntryModule);
  return FillTemplate(data,
                      "<script>" + CheckScriptSafe(three.three, three.three_path.string()) + "</script>\n<script>" +
                          CheckScriptSafe(three.orbit, three.orbit_path.string()) + "</script>",
                      "<script type=\"module\">\n" + CheckScriptSafe(bundle, "the viewer's modules") + "</script>");
}

ServedPage ServedViewerPage(const nlohmann::json& data) {
  ThreeJs three = ReadThreeJs();
  ServedPage page;
  page.html = FillTemplate(data,
                           "<script src=\"three/three.min.js\"></script>\n"
                           "<script src=\"three/OrbitControls.js\"></script>",
                           "<script type=\"module\" src=\"" + std::string(kEntryModule) + "\"></script>");
  page.files.push_back({"three/three.min.js", std::move(three.three), std::string(kScriptType)});
  page.files.push_back({"three/OrbitControls.js", std::move(three.orbit), std::string(kScriptType)});
  for (const std::string& name : ViewerModuleNames()) {
    page.files.push_back({name, std::string(EmbeddedWebFile(name)), std::string(kScriptType)});
  }
  return page;
}

}  // namespace contactlab
