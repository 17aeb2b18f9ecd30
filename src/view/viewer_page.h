// The viewer page: one self-contained HTML file (three.js r111 and its OrbitControls inlined from
// their installed files, the viewer's own HTML, CSS and JS embedded in the program at build time
// from src/view/web/, and the data of view_data.h). Nothing is fetched when the page is opened.
#pragma once

#include <filesystem>
#include <string>

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

// The page showing DATA. Throws Error naming the three.js file that is missing or unreadable
// and the package that provides it.
std::string ViewerPage(const nlohmann::json& data);

// The page's parts as embedded in the program (for tests): "viewer.html", "viewer.css",
// "viewer.js"; throws Error for another name.
std::string_view EmbeddedWebFile(std::string_view name);

}  // namespace contactlab
