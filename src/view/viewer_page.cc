#include "view/viewer_page.h"

#include <cctype>
#include <cstdlib>

#include "util/atomic_file.h"
#include "util/error.h"
#include "view/page_encoding.h"
#include "view/web_assets.h"

namespace contactlab {
namespace {

namespace fs = std::filesystem;

// Reads FILE of three.js, naming it and the package that provides it when it cannot.
std::string ReadThreeJsFile(const fs::path& file) {
  if (!fs::exists(file)) {
    Fail(file.string(), "not found: the viewer inlines three.js r111 from here; install Debian's libjs-three "
                        "(scripts/install-deps.sh) or point CONTACTLAB_THREEJS_DIR at a folder holding three.min.js "
                        "and examples/js/controls/OrbitControls.js");
  }
  return ReadWholeFile(file);
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
  if (name == "viewer.html") return web_assets::kViewerHtml;
  if (name == "viewer.css") return web_assets::kViewerCss;
  if (name == "viewer.js") return web_assets::kViewerJs;
  Fail("viewer", "no embedded web file " + QuoteToken(name));
}

std::string ViewerPage(const nlohmann::json& data) {
  const fs::path dir = ThreeJsDir();
  const fs::path three = dir / "three.min.js", orbit = dir / "examples/js/controls/OrbitControls.js";
  const std::string three_js = ReadThreeJsFile(three), orbit_js = ReadThreeJsFile(orbit);
  const std::string title = data.value("title", std::string("contactlab view"));
  std::string escaped;
  for (char c : title) {
    if (c == '<') escaped += "&lt;";
    else if (c == '>') escaped += "&gt;";
    else if (c == '&') escaped += "&amp;";
    else escaped += c;
  }
  std::string page(web_assets::kViewerHtml);
  std::size_t cursor = 0;
  Substitute(&page, &cursor, "@TITLE@", escaped);
  Substitute(&page, &cursor, "/*@VIEWER_CSS@*/", web_assets::kViewerCss);
  Substitute(&page, &cursor, "/*@THREE_JS@*/", CheckScriptSafe(three_js, three.string()));
  Substitute(&page, &cursor, "/*@ORBIT_CONTROLS_JS@*/", CheckScriptSafe(orbit_js, orbit.string()));
  Substitute(&page, &cursor, "@DATA@", ScriptSafeJson(data));
  Substitute(&page, &cursor, "/*@VIEWER_JS@*/", CheckScriptSafe(std::string(web_assets::kViewerJs), "viewer.js"));
  return page;
}

}  // namespace contactlab
