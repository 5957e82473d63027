#include "io/table_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace mechkin {

std::string CsvCell(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string JsonEscape(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c == '"' || c == '\\') { out += '\\'; out += static_cast<char>(c); }
    else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20) { char b[8]; std::snprintf(b, sizeof b, "\\u%04x", c); out += b; }
    else out += static_cast<char>(c);
  }
  return out;
}

std::string XmlEscape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '&': out += "&amp;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

TableWriter::TableWriter(const MotionLayout& layout, TableFormat format, OutputFile* file)
    : format_(format), file_(file) {
  std::string head;
  if (format == TableFormat::Csv) {
    for (size_t c = 0; c < layout.columns().size(); ++c) head += (c ? "," : "") + CsvCell(layout.columns()[c].Header());
    head += "\n";
  } else {
    head = "{\"columns\":[";
    for (size_t c = 0; c < layout.columns().size(); ++c) {
      const ColumnDescriptor& d = layout.columns()[c];
      head += std::string(c ? "," : "") + "{\"name\":\"" + JsonEscape(d.name) + "\",\"unit\":\"" + JsonEscape(d.unit) + "\"}";
    }
    head += "],\"rows\":[";
  }
  file_->Write(head);
}

// One number at `out` (room for kMaxNumberChars), returning its end. Exact zeros,
// nearly half of a typical table (planar and axis-aligned columns), skip to_chars:
// its shortest form of ±0 is "0" and "-0".
char* TableWriter::AppendNumber(double v, char* out) const {
  if (v == 0) {
    if (std::signbit(v)) *out++ = '-';
    *out++ = '0';
    return out;
  }
  if (format_ == TableFormat::Json && !std::isfinite(v)) {
    std::memcpy(out, "null", 4);
    return out + 4;
  }
  return std::to_chars(out, out + kMaxNumberChars, v).ptr;
}

// The row straight into one buffer sized once (no string appends per number).
bool TableWriter::Append(const double* row, int size) {
  const size_t room = static_cast<size_t>(size) * (kMaxNumberChars + 1) + 4;
  if (buffer_.size() < room) buffer_.resize(room);
  char* out = buffer_.data();
  if (format_ == TableFormat::Json) {
    if (!first_row_) *out++ = ',';
    *out++ = '[';
  }
  for (int c = 0; c < size; ++c) {
    if (c) *out++ = ',';
    out = AppendNumber(row[c], out);
  }
  *out++ = format_ == TableFormat::Json ? ']' : '\n';
  first_row_ = false;
  return file_->Write(buffer_.data(), static_cast<size_t>(out - buffer_.data()));
}

namespace {

std::string JsonNumber(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// ,"reductions":[...]: one object per reduction, NaN as null.
std::string ReductionsJson(const std::vector<ReductionResult>& reductions) {
  if (reductions.empty()) return "";
  std::string out = ",\"reductions\":[";
  for (size_t k = 0; k < reductions.size(); ++k) {
    const ReductionResult& r = reductions[k];
    out += std::string(k ? "," : "") + "{\"name\":\"" + JsonEscape(r.name) + "\",\"of\":\"" + JsonEscape(r.of) +
           "\",\"reduce\":\"" + ReduceKindName(r.kind) + "\",\"value\":" + JsonNumber(r.value) + ",\"unit\":\"" +
           JsonEscape(r.unit) + "\"";
    if (r.kind == ReduceKind::Min || r.kind == ReduceKind::Max || r.kind == ReduceKind::At)
      out += ",\"t\":" + JsonNumber(r.t);
    if (r.kind == ReduceKind::Sse) {
      out += ",\"residuals\":[";
      for (size_t i = 0; i < r.residuals.size(); ++i) out += std::string(i ? "," : "") + JsonNumber(r.residuals[i]);
      out += "]";
    }
    if (r.kind == ReduceKind::Min || r.kind == ReduceKind::Max) out += std::string(",\"located\":") + (r.located ? "true" : "false");
    if (!r.wrt.empty()) {
      out += ",\"gradient\":{";
      for (size_t p = 0; p < r.wrt.size(); ++p)
        out += std::string(p ? "," : "") + "\"" + JsonEscape(r.wrt[p]) + "\":" + JsonNumber(r.gradient[p]);
      out += "}";
    }
    if (!r.problem.empty()) out += ",\"problem\":\"" + JsonEscape(r.problem) + "\"";
    out += "}";
  }
  return out + "]";
}

}  // namespace

bool TableWriter::Finish(const std::string& partial_note, std::string* error,
                         const std::vector<ReductionResult>& reductions) {
  const bool partial = !partial_note.empty();
  if (format_ == TableFormat::Csv) return file_->Commit(partial ? "# PARTIAL TABLE: " + partial_note + "\n" : "", error);
  std::string tail = "],\"mechkin_table\":1";
  if (partial) tail += ",\"note\":\"" + JsonEscape(partial_note) + "\"";
  tail += ReductionsJson(reductions);
  tail += std::string(",\"partial\":") + (partial ? "true" : "false") + "}\n";
  file_->Write(tail);
  return file_->Commit("", error);
}

bool WriteMotion(const Motion& motion, TableFormat format, const std::string& path, std::string* error,
                 const std::vector<std::string>& inputs) {
  OutputFile file;
  if (!file.Open(path, inputs, error)) return false;
  TableWriter writer(motion.layout(), format, &file);
  for (int r = 0; r < motion.rows(); ++r) writer.Append(&motion.values()[static_cast<size_t>(r) * motion.cols()], motion.cols());
  return writer.Finish(motion.complete ? "" : motion.stop.Summary(), error, motion.reductions);
}

}  // namespace mechkin
