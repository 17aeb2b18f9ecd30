// The viewer page, in two forms from one template (src/view/web/viewer.html) and the same
// script files:
// - ViewerPage: one self-contained HTML file (`contactlab view`): three.js r111 and its
//   OrbitControls inlined from their installed files, the viewer's ES modules bundled into one
//   inline module (module_bundle.h; a page opened from file:// can load no module file), and
//   the data of view_data.h. Nothing is fetched when the page is opened.
// - ServedViewerPage: the page a session's live view serves (live_view_server.h), which loads
//   three.js and the viewer's modules as files from the same server.
// The viewer's own HTML, CSS and modules (src/view/web/) are embedded in the program at build
// time, so the program finds them wherever it is installed; three.js is read from Debian's
// libjs-three when a page is made.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace contactlab {

// The folder holding three.js (three.min.js, examples/js/controls/OrbitControls.js):
// $CONTACTLAB_THREEJS_DIR when set, else the folder the build was configured with
// (CMake option CONTACTLAB_THREEJS_DIR, default /usr/share/javascript/three, Debian's
// libjs-three).
std::filesystem::path ThreeJsDir();

// Throws Error naming the first of three.js's files (three.min.js, OrbitControls.js) in
// ThreeJsDir() that is missing, and the package that provides it; a command calls it before
// any work so that a missing package is reported at once.
void RequireThreeJs();

// The page showing DATA, self-contained. Throws Error naming the three.js file that is missing
// or unreadable and the package that provides it.
std::string ViewerPage(const nlohmann::json& data);

// A file a served page loads: its path below the page's folder ("viewer/main.js"), its content
// and its media type.
struct ServedFile {
  std::string path;
  std::string content;
  std::string content_type;
};

// A page and the files it loads, as a server serves them: the page at "/", each file at
// "/" + its path.
struct ServedPage {
  std::string html;
  std::vector<ServedFile> files;
};

// The page showing DATA with three.js ("three/three.min.js", "three/OrbitControls.js") and the
// viewer's modules ("viewer/*.js") as files beside it. Throws as ViewerPage.
ServedPage ServedViewerPage(const nlohmann::json& data);

// The page's parts as embedded in the program (for tests): "viewer.html", "viewer.css" and the
// modules "viewer/NAME.js"; throws Error for another name.
std::string_view EmbeddedWebFile(std::string_view name);

// The names of the viewer's embedded modules ("viewer/main.js", ...), in name order.
std::vector<std::string> ViewerModuleNames();

}  // namespace contactlab
