// Dataset files of `mechkin sweep --curves COLS --out DIR` (issue 31): HDF5 through
// Debian's libhdf5 (C API, 1.10), read by h5py/numpy without parsing text. The layout
// is docs/datasets.md: `curves` [variants, rows, columns] chunked one variant a chunk,
// `parameters`, `status` codes, `rows`, `t_stop`, `variant`, `t`, with the names,
// units, status names and the sweep's identity as attributes.
//
// A writer streams: each finished variant is written at its place and dropped, so
// memory does not grow with the variant count. A file is written under a temporary
// name and renamed into place when finished (a killed writer leaves no file that
// looks whole; a retried one replaces it). A merge makes one file of many whose
// datasets are HDF5 virtual datasets over the parts' (no data copied).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "analysis/sweep_curves.hpp"

namespace mechkin {

/// What a dataset file holds: the variants first + k·stride (k < count) of a sweep of
/// `total` variants, each `rows` rows of `columns`.
struct DatasetShape {
  std::vector<std::string> parameters, columns, units;
  int rows = 0;
  int total = 0;
  int first = 0, stride = 1, count = 0;
  int shard = 0, shards = 0;  // the CLI's --shard i/N (0: not a CLI shard)
  std::string identity;       // the sweep's identity, JSON text (a merge requires one identity)
  std::string source;         // the mechanism file
};

/// The shape of the file for a shard's variants (its variants first + k·stride).
DatasetShape ShapeOf(const ShardVariants& variants, const CurveSelection& selection);

class DatasetWriter {
 public:
  DatasetWriter();
  ~DatasetWriter();  // a writer not finished removes its temporary file
  DatasetWriter(const DatasetWriter&) = delete;
  DatasetWriter& operator=(const DatasetWriter&) = delete;

  /// Creates the file (under a temporary name beside `path`); false with `error` set.
  bool Create(const std::string& path, const DatasetShape& shape, std::string* error);
  /// Writes one variant at its position (VariantCurves::position).
  bool Write(const VariantCurves& variant, std::string* error);
  /// Closes the file and renames it into place; `partial` marks it (attribute complete = 0:
  /// a merge refuses it).
  bool Finish(bool partial, std::string* error);
  int written() const { return written_; }

 private:
  struct Handles;
  std::unique_ptr<Handles> h_;
  std::string path_, tmp_;
  int written_ = 0;
  bool t_written_ = false;
};

/// One file `out` over the parts (shards of one sweep, together every variant once):
/// virtual datasets that read the parts' data where it is, named by paths relative to
/// `out`'s folder (move the folder as a whole). False with `error` naming the problem
/// (a partial part, parts of different sweeps, missing or repeated variants).
bool MergeDatasets(const std::vector<std::string>& parts, const std::string& out, std::string* error);

}  // namespace mechkin
