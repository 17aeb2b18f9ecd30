// The temporary files this process is writing, kept where a signal handler can reach them: a
// fixed table of paths (no allocation, no locks) so that SIGINT, SIGTERM, SIGHUP or SIGQUIT in
// the middle of an atomic write unlinks the half-written "NAME.tmp-PID-N" (or empties and removes
// a staging folder "FOLDER.tmp-PID-N") before the process dies.
#pragma once

namespace contactlab {

// Records PATH as a temporary file being written; returns its slot, or -1 when the table is
// full or PATH is too long (the file is then only removed by its writer, not on a signal).
int RegisterTemporaryFile(const char* path);

// Records PATH as a staging folder of regular files being written (TemporaryFolder): on a signal
// its files are unlinked and it is removed. Returns its slot, or -1 as above.
int RegisterTemporaryFolder(const char* path);

// Forgets SLOT (from RegisterTemporaryFile; -1 is ignored) once the file was renamed or removed.
void UnregisterTemporaryFile(int slot);

// Unlinks every registered temporary file of this process, then empties and removes every
// registered staging folder. Async-signal-safe.
void UnlinkTemporaryFiles();

// Installs SIGINT, SIGTERM, SIGHUP and SIGQUIT handlers that unlink the registered temporary
// files and then re-raise the signal with its default action (so the exit status still says "killed by").
// Code that wants a clean stop instead (the haptic session) installs its own handler later.
void InstallTemporaryFileCleanupOnSignals();

}  // namespace contactlab
