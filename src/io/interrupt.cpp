#include "io/interrupt.hpp"

#include <unistd.h>

#include <csignal>
#include <cstring>

namespace mechkin {
namespace {

constexpr int kSlots = 4;
constexpr int kPathMax = 4096;
// Written only outside the handler; the handler reads them (async-signal-safe:
// fixed buffers, unlink, signal, raise).
char g_paths[kSlots][kPathMax];
volatile std::sig_atomic_t g_used[kSlots];
volatile std::sig_atomic_t g_keep_partial = 0;
volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void OnSignal(int sig) {
  if (sig == SIGINT && g_keep_partial && !g_interrupted) {
    g_interrupted = 1;  // the run stops at its next row and writes a partial table
    return;
  }
  for (int k = 0; k < kSlots; ++k)
    if (g_used[k]) ::unlink(g_paths[k]);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

}  // namespace

void InstallInterruptHandlers(bool keep_partial_on_sigint) {
  g_keep_partial = keep_partial_on_sigint ? 1 : 0;
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);
}

bool InterruptRequested() { return g_interrupted != 0; }

void RegisterTemporaryFile(const char* path) {
  if (std::strlen(path) >= kPathMax) return;
  for (int k = 0; k < kSlots; ++k)
    if (!g_used[k]) {
      std::strcpy(g_paths[k], path);
      g_used[k] = 1;
      return;
    }
}

void UnregisterTemporaryFile(const char* path) {
  for (int k = 0; k < kSlots; ++k)
    if (g_used[k] && std::strcmp(g_paths[k], path) == 0) g_used[k] = 0;
}

}  // namespace mechkin
