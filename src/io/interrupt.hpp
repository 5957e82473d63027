// SIGINT / SIGTERM while a table is being written: the temporary file is
// removed (the target keeps its old content), or — on SIGINT with
// --keep-partial — the run stops at the next row and writes what it has as a
// partial table.
#pragma once

namespace mechkin {

/// Installs the handlers (once per process).
void InstallInterruptHandlers(bool keep_partial_on_sigint);
/// True after a SIGINT that asked for a partial table.
bool InterruptRequested();
/// The temporary files a signal must remove (OutputFile registers its own).
void RegisterTemporaryFile(const char* path);
void UnregisterTemporaryFile(const char* path);

}  // namespace mechkin
