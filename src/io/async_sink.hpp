// Formats and writes rows on a second thread while the analysis computes the
// next ones: on a 2-core machine the table's text formatting (std::to_chars,
// ~40% of a full-table run of the slider-crank) overlaps the solve instead of
// adding to it. Rows travel in fixed chunks through a bounded queue, so memory
// stays independent of the number of steps.
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>
#include <vector>

#include "analysis/motion.hpp"

namespace mechkin {

class AsyncRowSink : public RowSink {
 public:
  /// Rows are handed to `inner` on the writer thread, in order.
  AsyncRowSink(RowSink* inner, int columns, int rows_per_chunk = 512, int max_chunks = 8);
  ~AsyncRowSink() override;
  AsyncRowSink(const AsyncRowSink&) = delete;
  AsyncRowSink& operator=(const AsyncRowSink&) = delete;

  /// Copies the row; false once the inner sink has failed.
  bool Append(const double* row, int size) override;
  /// Hands over the last rows and waits until the writer thread is done.
  /// Returns false when the inner sink failed on some row.
  bool Drain();

 private:
  void Hand(std::vector<double> chunk);
  void Work();

  RowSink* inner_;
  int columns_;
  size_t chunk_values_;
  int max_chunks_;
  std::vector<double> current_;
  std::deque<std::vector<double>> queue_, free_;
  int chunks_alive_ = 0;
  std::mutex mutex_;
  std::condition_variable work_ready_, chunk_free_;
  bool done_ = false;
  std::atomic<bool> failed_{false};
  std::thread worker_;
};

}  // namespace mechkin
