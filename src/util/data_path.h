// The data search path (docs/architecture.md "Data search path and cache"). A name
// ("dragon.obj", "scenes/dragon-bunny.yaml") is resolved, first hit wins, from:
//   1. the name as given when it is absolute;
//   2. the folder of the scene or config file that names it (BASE_DIR), when there is one;
//   3. the name as given, relative to the working folder;
//   4. $CONTACTLAB_DATA;
//   5. the installed data folder: <folder of the running program>/../share/contactlab/data
//      (the build tree mirrors this layout: build/share/contactlab/data is the repository's
//      data/), then its parent share/contactlab (experiments/ and scripts/ live there); in a
//      program that is not ContactLab's own (the Python module), the share/contactlab folder
//      it names with SetInstalledRoot;
//   6. ../shared/data beside the working folder and beside the repository, when present.
// In each data folder a bare name is also looked for under meshes/, and "NAME" also matches
// "NAME.gz" (meshes ship gzip-compressed: "dragon.obj" finds meshes/dragon.obj.gz).
// Nothing here depends on where the program was built.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace contactlab {

// The folders of steps 4-6, in order (only those that exist, each once).
std::vector<std::filesystem::path> DataSearchPath();

// The installed data folder of step 5 (it holds meshes/, scenes/, trajectories/), or nullopt
// when it does not exist beside the running program.
std::optional<std::filesystem::path> InstalledDataDir();

// Step 5's share/contactlab folder for a host program that is not ContactLab's own: the Python
// module finds it above its package (PREFIX/share/contactlab, or build/share/contactlab in a
// build tree) and names it here at import. Ignored unless ROOT/data is a folder.
void SetInstalledRoot(const std::filesystem::path& root);

// Resolves NAME as above. BASE_DIR: the folder of the file that names NAME (empty: none).
// Returns nullopt when nothing is found.
std::optional<std::filesystem::path> FindDataFile(std::string_view name, const std::filesystem::path& base_dir = {});

// As FindDataFile, but throws Error naming NAME and every folder searched.
std::filesystem::path RequireDataFile(std::string_view name, const std::filesystem::path& base_dir = {});

// The folder holding FILE ("." for a bare file name): the BASE_DIR for names read from FILE.
std::filesystem::path FolderOf(const std::filesystem::path& file);

}  // namespace contactlab
