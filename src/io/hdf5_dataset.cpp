#include "io/hdf5_dataset.hpp"

#include <hdf5.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>

#include "io/interrupt.hpp"
#include "math/numbers.hpp"

namespace mechkin {

namespace {

// An HDF5 identifier closed by its own close function when it goes out of scope.
class Hid {
 public:
  Hid() = default;
  Hid(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Hid(Hid&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  Hid& operator=(Hid&& o) noexcept {
    Reset();
    id_ = o.id_, close_ = o.close_, o.id_ = -1;
    return *this;
  }
  ~Hid() { Reset(); }
  void Reset() {
    if (id_ >= 0 && close_) close_(id_);
    id_ = -1;
  }
  hid_t Release() {
    const hid_t id = id_;
    id_ = -1;
    return id;
  }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

// HDF5's own error printing is off: failures are reported with the file and the step.
void Quiet() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

// Memory that does not grow with the variant count (issue 31: "memory stays flat"). Two
// HDF5 defaults grow with a file of many chunks (one chunk a variant): the metadata
// cache resizes itself up to 32 MB as the chunk index grows, and the free lists keep
// every block HDF5 ever freed for reuse, unbounded. Both get fixed small limits here;
// the index pages evicted from the cache are written and read again when needed.
void BoundCaches(hid_t file_access) {
  H5AC_cache_config_t config;
  config.version = H5AC__CURR_CACHE_CONFIG_VERSION;
  if (H5Pget_mdc_config(file_access, &config) >= 0) {
    constexpr size_t kCacheBytes = 2 << 20;
    config.set_initial_size = true;
    config.initial_size = kCacheBytes;
    config.max_size = kCacheBytes;
    config.min_size = kCacheBytes / 2;
    config.incr_mode = H5C_incr__off;
    config.flash_incr_mode = H5C_flash_incr__off;
    config.decr_mode = H5C_decr__off;
    H5Pset_mdc_config(file_access, &config);
  }
  constexpr int kFreeListBytes = 1 << 20;  // per kind of free list, and per list
  H5set_free_list_limits(kFreeListBytes, kFreeListBytes / 4, kFreeListBytes, kFreeListBytes / 4, kFreeListBytes,
                         kFreeListBytes / 4);
}

Hid Space(const std::vector<hsize_t>& dims) {
  return Hid(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
}

Hid VlenString() {
  Hid t(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(t.get(), H5T_VARIABLE);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

bool StringsAttribute(hid_t on, const char* name, const std::vector<std::string>& values) {
  const Hid type = VlenString();
  const Hid space = Space({values.size()});
  std::vector<const char*> pointers;
  for (const auto& v : values) pointers.push_back(v.c_str());
  const Hid a(H5Acreate2(on, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return a.ok() && H5Awrite(a.get(), type.get(), pointers.data()) >= 0;
}

bool StringAttribute(hid_t on, const char* name, const std::string& value) {
  const Hid type = VlenString();
  const Hid space(H5Screate(H5S_SCALAR), H5Sclose);
  const char* p = value.c_str();
  const Hid a(H5Acreate2(on, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return a.ok() && H5Awrite(a.get(), type.get(), &p) >= 0;
}

bool IntAttribute(hid_t on, const char* name, long long value) {
  const Hid space(H5Screate(H5S_SCALAR), H5Sclose);
  const Hid a(H5Acreate2(on, name, H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  return a.ok() && H5Awrite(a.get(), H5T_NATIVE_LLONG, &value) >= 0;
}

bool ReadInt(hid_t on, const char* name, long long* value) {
  const Hid a(H5Aopen(on, name, H5P_DEFAULT), H5Aclose);
  return a.ok() && H5Aread(a.get(), H5T_NATIVE_LLONG, value) >= 0;
}

// A string or string-list attribute (variable-length UTF-8, as this file writes them).
bool ReadStrings(hid_t on, const char* name, std::vector<std::string>* values) {
  const Hid a(H5Aopen(on, name, H5P_DEFAULT), H5Aclose);
  if (!a.ok()) return false;
  const Hid space(H5Aget_space(a.get()), H5Sclose);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  if (n < 0) return false;
  std::vector<char*> pointers(static_cast<size_t>(n), nullptr);
  const Hid type = VlenString();
  if (H5Aread(a.get(), type.get(), pointers.data()) < 0) return false;
  values->clear();
  for (char* p : pointers) values->push_back(p ? p : "");
  H5Dvlen_reclaim(type.get(), space.get(), H5P_DEFAULT, pointers.data());
  return true;
}

// The properties of a dataset of `dims`: chunks of `chunk` (none for an empty one), the fill value.
Hid Creation(const std::vector<hsize_t>& dims, const std::vector<hsize_t>& chunk, hid_t type, const void* fill) {
  Hid p(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (dims.front() > 0) H5Pset_chunk(p.get(), static_cast<int>(chunk.size()), chunk.data());
  H5Pset_fill_value(p.get(), type, fill);
  return p;
}

// A dataset's chunk cache of `chunks` chunks of `chunk` (8-byte values at most): the
// variants finish in nearly ascending order, so a few chunks hold the ones being
// written; the default 1 MB a dataset would keep finished chunks of the small
// per-variant datasets, growing with the variant count up to 5 MB.
Hid ChunkCache(const std::vector<hsize_t>& chunk, size_t chunks) {
  Hid p(H5Pcreate(H5P_DATASET_ACCESS), H5Pclose);
  size_t bytes = 8;
  for (hsize_t n : chunk) bytes *= static_cast<size_t>(n);
  H5Pset_chunk_cache(p.get(), 521, bytes * chunks, 1.0);  // w0 = 1: evict fully written chunks first
  return p;
}

struct Column {
  const char* name;
  hid_t file_type, memory_type;
};
// The per-variant datasets besides `curves`, in the order Handles keeps them.
const Column kPerVariant[] = {{"parameters", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE},
                              {"status", H5T_STD_I32LE, H5T_NATIVE_INT},
                              {"rows", H5T_STD_I32LE, H5T_NATIVE_INT},
                              {"t_stop", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE},
                              {"variant", H5T_STD_I64LE, H5T_NATIVE_LLONG}};
constexpr int kParameters = 0, kStatus = 1, kRows = 2, kTStop = 3, kVariant = 4, kPerVariantCount = 5;

// The fill value of a per-variant dataset (what an unwritten variant reads as).
const void* FillOf(int which) {
  static const double nan = kNaN;
  static const int minus_one = -1;
  static const long long minus_one_ll = -1;
  if (which == kVariant) return &minus_one_ll;
  return which == kParameters || which == kTStop ? static_cast<const void*>(&nan) : &minus_one;
}

// The dims of dataset `which` (−1: curves) in a file of `shape` with `count` variants.
std::vector<hsize_t> DimsOf(int which, const DatasetShape& shape, hsize_t count) {
  if (which < 0) return {count, static_cast<hsize_t>(shape.rows), shape.columns.size()};
  if (which == kParameters) return {count, shape.parameters.size()};
  return {count};
}

// The attributes that describe the datasets (names, units, codes), on the file `f`.
bool Describe(hid_t f, const DatasetShape& shape) {
  const Hid curves(H5Dopen2(f, "curves", H5P_DEFAULT), H5Dclose);
  const Hid parameters(H5Dopen2(f, "parameters", H5P_DEFAULT), H5Dclose);
  const Hid status(H5Dopen2(f, "status", H5P_DEFAULT), H5Dclose);
  const Hid t(H5Dopen2(f, "t", H5P_DEFAULT), H5Dclose);
  return StringsAttribute(curves.get(), "columns", shape.columns) &&
         StringsAttribute(curves.get(), "units", shape.units) &&
         StringsAttribute(parameters.get(), "names", shape.parameters) &&
         StringsAttribute(status.get(), "names", SweepStatusNames()) && StringAttribute(t.get(), "unit", "s") &&
         IntAttribute(f, "mechkin_dataset", 1) && StringAttribute(f, "sweep", shape.identity) &&
         StringAttribute(f, "source", shape.source) && IntAttribute(f, "total", shape.total) &&
         IntAttribute(f, "first", shape.first) && IntAttribute(f, "stride", shape.stride) &&
         IntAttribute(f, "count", shape.count) && IntAttribute(f, "shard", shape.shard) &&
         IntAttribute(f, "shards", shape.shards);
}

// `t` [rows]: the rows' times (written from the first complete variant).
bool CreateTime(hid_t f, const DatasetShape& shape) {
  const Hid space = Space({static_cast<hsize_t>(shape.rows)});
  Hid p(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_fill_value(p.get(), H5T_NATIVE_DOUBLE, &kNaN);
  const Hid d(H5Dcreate2(f, "t", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, p.get(), H5P_DEFAULT), H5Dclose);
  return d.ok();
}

// A temporary name beside `path` (created exclusively, so two writers never share one).
bool TemporaryBeside(const std::string& path, std::string* tmp, std::string* error) {
  std::string name = path + ".partial-XXXXXX";
  const int fd = ::mkstemp(name.data());
  if (fd < 0) {
    *error = "cannot create a file beside '" + path + "': " + std::strerror(errno);
    return false;
  }
  const mode_t mask = ::umask(0);  // a regular file's mode (mkstemp makes it 0600)
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
  *tmp = name;
  return true;
}

}  // namespace

struct DatasetWriter::Handles {
  Hid file, curves, t;
  Hid per_variant[kPerVariantCount];
  DatasetShape shape;
};

DatasetWriter::DatasetWriter() = default;

DatasetWriter::~DatasetWriter() {
  if (!h_) return;
  h_.reset();
  std::remove(tmp_.c_str());
  UnregisterTemporaryFile(tmp_.c_str());
}

DatasetShape ShapeOf(const ShardVariants& variants, const CurveSelection& selection) {
  DatasetShape s;
  s.parameters = variants.parameters;
  s.columns = selection.names;
  s.units = selection.units;
  s.rows = selection.rows;
  s.total = variants.total;
  s.count = static_cast<int>(variants.size());
  s.first = variants.first();
  s.stride = variants.stride();
  return s;
}

bool DatasetWriter::Create(const std::string& path, const DatasetShape& shape, std::string* error) {
  Quiet();
  path_ = path;
  if (!TemporaryBeside(path, &tmp_, error)) return false;
  RegisterTemporaryFile(tmp_.c_str());  // a signal removes it (io/interrupt.hpp)
  h_ = std::make_unique<Handles>();
  h_->shape = shape;
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_LATEST);
  BoundCaches(fapl.get());
  h_->file = Hid(H5Fcreate(tmp_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  bool ok = h_->file.ok();
  const hsize_t count = static_cast<hsize_t>(shape.count);
  for (int which = -1; ok && which < kPerVariantCount; ++which) {
    const std::vector<hsize_t> dims = DimsOf(which, shape, count);
    std::vector<hsize_t> chunk = dims;
    chunk[0] = which < 0 ? 1 : std::min<hsize_t>(std::max<hsize_t>(count, 1), 4096);
    const hid_t type = which < 0 ? H5T_IEEE_F64LE : kPerVariant[which].file_type;
    const Hid p = Creation(dims, chunk, which < 0 ? H5T_NATIVE_DOUBLE : kPerVariant[which].memory_type,
                           which < 0 ? &kNaN : FillOf(which));
    const Hid space = Space(dims);
    const Hid access = ChunkCache(chunk, which < 0 ? 64 : 2);
    Hid d(H5Dcreate2(h_->file.get(), which < 0 ? "curves" : kPerVariant[which].name, type, space.get(), H5P_DEFAULT,
                     p.get(), access.get()), H5Dclose);
    ok = d.ok();
    (which < 0 ? h_->curves : h_->per_variant[which]) = std::move(d);
  }
  ok = ok && CreateTime(h_->file.get(), shape) && Describe(h_->file.get(), shape) &&
       IntAttribute(h_->file.get(), "complete", 0);
  if (ok) h_->t = Hid(H5Dopen2(h_->file.get(), "t", H5P_DEFAULT), H5Dclose);
  if (!ok) *error = "cannot create the HDF5 file '" + tmp_ + "' (for '" + path + "')";
  return ok;
}

namespace {

// Writes `values` (rows of `dims` past the first) at row `row` of the dataset `d`.
bool WriteRow(hid_t d, hsize_t row, std::vector<hsize_t> dims, hid_t memory_type, const void* values) {
  const Hid file_space(H5Dget_space(d), H5Sclose);
  std::vector<hsize_t> start(dims.size(), 0);
  start[0] = row;
  dims[0] = 1;
  const Hid memory = Space(dims);
  return H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, dims.data(), nullptr) >= 0 &&
         H5Dwrite(d, memory_type, memory.get(), file_space.get(), H5P_DEFAULT, values) >= 0;
}

}  // namespace

bool DatasetWriter::Write(const VariantCurves& v, std::string* error) {
  const DatasetShape& s = h_->shape;
  const hsize_t row = static_cast<hsize_t>(v.position);
  const int status = SweepStatusCode(v.status);
  const long long index = v.index;
  bool ok = v.position >= 0 && v.position < s.count && v.values.size() == s.parameters.size();
  if (ok && v.rows > 0)
    ok = WriteRow(h_->curves.get(), row, {1, static_cast<hsize_t>(v.rows), s.columns.size()}, H5T_NATIVE_DOUBLE,
                  v.curves.data());
  ok = ok && WriteRow(h_->per_variant[kParameters].get(), row, {1, s.parameters.size()}, H5T_NATIVE_DOUBLE,
                      v.values.data()) &&
       WriteRow(h_->per_variant[kStatus].get(), row, {1}, H5T_NATIVE_INT, &status) &&
       WriteRow(h_->per_variant[kRows].get(), row, {1}, H5T_NATIVE_INT, &v.rows) &&
       WriteRow(h_->per_variant[kTStop].get(), row, {1}, H5T_NATIVE_DOUBLE, &v.t_stop) &&
       WriteRow(h_->per_variant[kVariant].get(), row, {1}, H5T_NATIVE_LLONG, &index);
  if (ok && !t_written_ && v.rows == s.rows) {
    ok = H5Dwrite(h_->t.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.t.data()) >= 0;
    t_written_ = true;
  }
  if (!ok) {
    *error = "cannot write variant " + std::to_string(v.index) + " to '" + tmp_ + "' (" +
             (errno ? std::strerror(errno) : "HDF5 write failed") + ")";
    return false;
  }
  ++written_;
  return true;
}

bool DatasetWriter::Finish(bool partial, std::string* error) {
  bool ok = h_ && IntAttribute(h_->file.get(), "written", written_);
  if (ok && !partial) {
    const Hid a(H5Aopen(h_->file.get(), "complete", H5P_DEFAULT), H5Aclose);
    const long long one = 1;
    ok = a.ok() && H5Awrite(a.get(), H5T_NATIVE_LLONG, &one) >= 0;
  }
  ok = ok && H5Fflush(h_->file.get(), H5F_SCOPE_GLOBAL) >= 0;
  h_->curves.Reset();
  h_->t.Reset();
  for (Hid& d : h_->per_variant) d.Reset();
  ok = H5Fclose(h_->file.Release()) >= 0 && ok;
  h_.reset();
  UnregisterTemporaryFile(tmp_.c_str());
  if (ok && std::rename(tmp_.c_str(), path_.c_str()) != 0) {
    *error = "cannot rename '" + tmp_ + "' to '" + path_ + "': " + std::strerror(errno);
    std::remove(tmp_.c_str());
    return false;
  }
  if (!ok) {
    *error = "cannot finish the HDF5 file '" + tmp_ + "' (a full disk?)";
    std::remove(tmp_.c_str());
  }
  return ok;
}

namespace {

// A part of a merge: its shape (read from its attributes) and where the merged file finds it.
struct Part {
  std::string path, relative;
  DatasetShape shape;
  long long complete = 0;
  std::vector<double> t;
};

bool ReadShape(hid_t f, DatasetShape* s) {
  long long v[8] = {};
  const char* keys[] = {"total", "first", "stride", "count", "shard", "shards", "mechkin_dataset"};
  for (int k = 0; k < 7; ++k)
    if (!ReadInt(f, keys[k], &v[k])) return false;
  s->total = static_cast<int>(v[0]), s->first = static_cast<int>(v[1]), s->stride = static_cast<int>(v[2]);
  s->count = static_cast<int>(v[3]), s->shard = static_cast<int>(v[4]), s->shards = static_cast<int>(v[5]);
  std::vector<std::string> one;
  const Hid curves(H5Dopen2(f, "curves", H5P_DEFAULT), H5Dclose);
  const Hid parameters(H5Dopen2(f, "parameters", H5P_DEFAULT), H5Dclose);
  if (!curves.ok() || !parameters.ok() || !ReadStrings(curves.get(), "columns", &s->columns) ||
      !ReadStrings(curves.get(), "units", &s->units) || !ReadStrings(parameters.get(), "names", &s->parameters))
    return false;
  const Hid space(H5Dget_space(curves.get()), H5Sclose);
  hsize_t dims[3] = {};
  if (H5Sget_simple_extent_ndims(space.get()) != 3 || H5Sget_simple_extent_dims(space.get(), dims, nullptr) < 0)
    return false;
  s->rows = static_cast<int>(dims[1]);
  if (!ReadStrings(f, "sweep", &one) || one.size() != 1) return false;
  s->identity = one.front();
  if (!ReadStrings(f, "source", &one) || one.size() != 1) return false;
  s->source = one.front();
  return s->stride >= 1 && s->count >= 0 && s->first >= 0 && s->total >= 0 &&
         (s->count == 0 || s->first + (s->count - 1LL) * s->stride < s->total) && dims[0] == hsize_t(s->count);
}

bool ReadPart(const std::string& path, const std::string& out_folder, Part* part, std::string* error) {
  part->path = path;
  part->relative = std::filesystem::absolute(path).lexically_normal().lexically_relative(out_folder).string();
  std::error_code exists_error;
  if (!std::filesystem::is_regular_file(path, exists_error)) {
    *error = "cannot open '" + path + "': no such file";
    return false;
  }
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    *error = "'" + path + "' is not an HDF5 file (a dataset written by sweep --curves --out)";
    return false;
  }
  const Hid f(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  if (!f.ok() || !ReadShape(f.get(), &part->shape) || !ReadInt(f.get(), "complete", &part->complete)) {
    *error = "'" + path + "' is not a mechkin dataset (attributes or datasets missing or damaged)";
    return false;
  }
  if (!part->complete) {
    *error = "'" + path + "' is a partial dataset (interrupted): run that part again to the end, then merge";
    return false;
  }
  const Hid t(H5Dopen2(f.get(), "t", H5P_DEFAULT), H5Dclose);
  part->t.assign(part->shape.rows, kNaN);
  return t.ok() && H5Dread(t.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, part->t.data()) >= 0;
}

// Parts of one sweep: the same identity, parameters, columns, units, rows and total.
bool SameSweep(const Part& a, const Part& b, std::string* error) {
  const DatasetShape &x = a.shape, &y = b.shape;
  std::string what;
  if (x.identity != y.identity) what = "the sweep (file, settings, variants)";
  else if (x.parameters != y.parameters) what = "the parameters";
  else if (x.columns != y.columns || x.units != y.units) what = "the columns";
  else if (x.rows != y.rows || x.total != y.total) what = "the rows or the variant count";
  if (what.empty()) return true;
  *error = "'" + b.path + "' is a part of another sweep than '" + a.path + "' (they differ in " + what +
           "): merge the parts of one sweep";
  return false;
}

// Every variant 0..total−1 in exactly one part; else the missing or repeated ones named.
bool EveryVariantOnce(const std::vector<Part>& parts, std::string* error) {
  const int total = parts.front().shape.total;
  std::vector<unsigned char> seen(static_cast<size_t>(total), 0);
  for (const Part& p : parts)
    for (long long i = p.shape.first, k = 0; k < p.shape.count; ++k, i += p.shape.stride)
      if (++seen[i] > 1) {
        *error = "variant " + std::to_string(i) + " is in two parts (one is '" + p.path + "'): merge each part once";
        return false;
      }
  std::string missing;
  int missing_count = 0;
  for (int i = 0; i < total; ++i)
    if (!seen[i] && ++missing_count <= 10) missing += (missing.empty() ? "" : ", ") + std::to_string(i);
  if (missing_count == 0) return true;
  if (missing_count > 10) missing += " and " + std::to_string(missing_count - 10) + " more";
  std::string shards;
  const int n = parts.front().shape.shards;
  if (n > 0)
    for (int s = 1; s <= n; ++s)
      if (std::none_of(parts.begin(), parts.end(), [&](const Part& p) { return p.shape.shard == s; }))
        shards += (shards.empty() ? "" : ", ") + std::to_string(s) + "/" + std::to_string(n);
  *error = (shards.empty() ? "" : "missing shards: " + shards + "; ") + "missing variants: " + missing + " (of 0.." +
           std::to_string(total - 1) + ")";
  return false;
}

// Dataset `which` (−1: curves) of the merged file: a virtual dataset over the parts'.
bool CreateVirtual(hid_t out, int which, const DatasetShape& whole, const std::vector<Part>& parts) {
  const std::vector<hsize_t> dims = DimsOf(which, whole, static_cast<hsize_t>(whole.total));
  const char* name = which < 0 ? "curves" : kPerVariant[which].name;
  Hid p(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_fill_value(p.get(), which < 0 ? H5T_NATIVE_DOUBLE : kPerVariant[which].memory_type,
                    which < 0 ? &kNaN : FillOf(which));
  const Hid space = Space(dims);
  for (const Part& part : parts) {
    if (part.shape.count == 0) continue;
    const std::vector<hsize_t> source_dims = DimsOf(which, whole, static_cast<hsize_t>(part.shape.count));
    const Hid source = Space(source_dims);
    const Hid target = Space(dims);
    std::vector<hsize_t> start(dims.size(), 0), stride(dims.size(), 1), count(dims.size(), 1), block = dims;
    start[0] = static_cast<hsize_t>(part.shape.first);
    stride[0] = static_cast<hsize_t>(part.shape.stride);
    count[0] = static_cast<hsize_t>(part.shape.count);
    block[0] = 1;
    if (H5Sselect_hyperslab(target.get(), H5S_SELECT_SET, start.data(), stride.data(), count.data(), block.data()) < 0 ||
        H5Pset_virtual(p.get(), target.get(), part.relative.c_str(), name, source.get()) < 0)
      return false;
  }
  const hid_t type = which < 0 ? H5T_IEEE_F64LE : kPerVariant[which].file_type;
  const Hid d(H5Dcreate2(out, name, type, space.get(), H5P_DEFAULT, p.get(), H5P_DEFAULT), H5Dclose);
  return d.ok();
}

// The merged file's own `t`: the first part's that holds a complete run.
bool WriteMergedTime(hid_t out, const DatasetShape& whole, const std::vector<Part>& parts) {
  if (!CreateTime(out, whole)) return false;
  for (const Part& p : parts)
    if (!p.t.empty() && !std::isnan(p.t.front())) {
      const Hid t(H5Dopen2(out, "t", H5P_DEFAULT), H5Dclose);
      return H5Dwrite(t.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, p.t.data()) >= 0;
    }
  return true;
}

}  // namespace

bool MergeDatasets(const std::vector<std::string>& files, const std::string& out, std::string* error) {
  Quiet();
  if (files.empty()) {
    *error = "no parts to merge";
    return false;
  }
  const std::string folder = std::filesystem::absolute(out).lexically_normal().parent_path().string();
  std::vector<Part> parts(files.size());
  for (size_t k = 0; k < files.size(); ++k) {
    std::error_code same_error;
    if (std::filesystem::equivalent(files[k], out, same_error)) {
      *error = "'" + files[k] + "' is the merged file itself: write the merge to another name";
      return false;
    }
    if (!ReadPart(files[k], folder, &parts[k], error) || !SameSweep(parts.front(), parts[k], error)) return false;
  }
  if (!EveryVariantOnce(parts, error)) return false;
  DatasetShape whole = parts.front().shape;
  whole.first = 0, whole.stride = 1, whole.count = whole.total, whole.shard = 0, whole.shards = 0;
  std::string tmp;
  if (!TemporaryBeside(out, &tmp, error)) return false;
  RegisterTemporaryFile(tmp.c_str());
  Hid fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V110, H5F_LIBVER_LATEST);
  Hid f(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get()), H5Fclose);
  bool ok = f.ok();
  for (int which = -1; ok && which < kPerVariantCount; ++which) ok = CreateVirtual(f.get(), which, whole, parts);
  std::vector<std::string> names;
  for (const Part& p : parts) names.push_back(p.relative);
  ok = ok && WriteMergedTime(f.get(), whole, parts) && Describe(f.get(), whole) &&
       StringsAttribute(f.get(), "parts", names) && IntAttribute(f.get(), "complete", 1) &&
       IntAttribute(f.get(), "written", whole.total);
  ok = H5Fclose(f.Release()) >= 0 && ok;
  UnregisterTemporaryFile(tmp.c_str());
  if (ok && std::rename(tmp.c_str(), out.c_str()) == 0) return true;
  *error = ok ? "cannot rename '" + tmp + "' to '" + out + "': " + std::strerror(errno)
              : "cannot write the merged HDF5 file '" + out + "'";
  std::remove(tmp.c_str());
  return false;
}

}  // namespace mechkin
