#include "io/async_sink.hpp"

namespace mechkin {

AsyncRowSink::AsyncRowSink(RowSink* inner, int columns, int rows_per_chunk, int max_chunks)
    : inner_(inner), columns_(columns), chunk_values_(static_cast<size_t>(columns) * rows_per_chunk),
      max_chunks_(max_chunks) {
  current_.reserve(chunk_values_);
  chunks_alive_ = 1;
  worker_ = std::thread([this] { Work(); });
}

AsyncRowSink::~AsyncRowSink() { Drain(); }

void AsyncRowSink::Hand(std::vector<double> chunk) {
  std::unique_lock<std::mutex> lock(mutex_);
  queue_.push_back(std::move(chunk));
  work_ready_.notify_one();
  // A fresh chunk: a recycled one, a new one while under the bound, else wait.
  chunk_free_.wait(lock, [&] { return !free_.empty() || chunks_alive_ < max_chunks_; });
  if (!free_.empty()) {
    current_ = std::move(free_.front());
    free_.pop_front();
  } else {
    ++chunks_alive_;
    current_ = std::vector<double>();
    current_.reserve(chunk_values_);
  }
  current_.clear();
}

bool AsyncRowSink::Append(const double* row, int size) {
  if (failed_) return false;
  current_.insert(current_.end(), row, row + size);
  if (current_.size() + columns_ > chunk_values_) Hand(std::move(current_));
  return true;
}

void AsyncRowSink::Work() {
  for (;;) {
    std::vector<double> chunk;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      work_ready_.wait(lock, [&] { return !queue_.empty() || done_; });
      if (queue_.empty()) return;
      chunk = std::move(queue_.front());
      queue_.pop_front();
    }
    for (size_t at = 0; at + columns_ <= chunk.size() && !failed_; at += columns_)
      if (!inner_->Append(&chunk[at], columns_)) failed_ = true;
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(chunk));
    chunk_free_.notify_one();
  }
}

bool AsyncRowSink::Drain() {
  if (!worker_.joinable()) return !failed_;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!current_.empty()) queue_.push_back(std::move(current_));
    current_.clear();
    done_ = true;
  }
  work_ready_.notify_one();
  worker_.join();
  return !failed_;
}

}  // namespace mechkin
