#include "io/vectors.h"

#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <ostream>
#include <stdexcept>

#include "io/atomic_file.h"
#include "io/input_source.h"
#include "io/line_reader.h"
#include "io/vector_blocks.h"
#include "io/vector_header.h"
#include "io/vector_rows.h"
#include "io/vector_rules.h"
#include "io/vector_syntax.h"

namespace glint {

namespace {

void append_double(std::string& out, double v) {
  char tmp[32];
  const auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  out.append(tmp, r.ptr);
}

void append_int(std::string& out, std::int64_t v) {
  char tmp[24];
  const auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  out.append(tmp, r.ptr);
}

bool is_white(const std::array<double, 3>& c) {
  return c[0] == 1 && c[1] == 1 && c[2] == 1;
}

}  // namespace

std::size_t VectorHeader::material_index(std::string_view name) const {
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == name) return i;
  }
  return npos;
}

std::array<double, 3> VectorHeader::intensity(int index) const {
  if (index < 0 || index >= lights) {
    throw std::out_of_range("VectorHeader::intensity: light " + std::to_string(index) +
                            " out of range (lights " + std::to_string(lights) + ")");
  }
  if (light_intensity.empty()) return {1, 1, 1};
  return light_intensity.at(static_cast<std::size_t>(index));
}

// ---- Reader ----------------------------------------------------------------------------------

// One part per job: LineReader (chunked input, the rules of every line), read_vector_header
// (vector_header.cpp), RowParser (vector_rows.cpp). The rules they check are in vector_syntax.h
// and vector_rules.h, shared with validate() (vector_rules.cpp) and the writer below.
struct VectorReader::Impl {
  std::unique_ptr<std::istream> owned;  // the stream, when the reader owns it
  LineReader lines;
  VectorFileHeader file;  // read by the constructor
  MaterialLookup materials;
  RowParser rows;
  std::unique_ptr<BlockParser> blocks;  // made by the first next_block()
  std::uint64_t rows_read = 0;
  std::unique_ptr<InputError> error;  // the first row error, rethrown by every later next()

  Impl(std::unique_ptr<std::istream> owned_file, std::istream& in, std::string name)
      : owned(std::move(owned_file)),
        lines(in, std::move(name)),
        file(read_vector_header(lines)),
        materials(file.header.materials),
        rows(lines.file(), file, materials) {}

  // Here rather than in RowParser so that LineReader::next() inlines into VectorReader::next().
  bool next(VectorRow& row) {
    std::string_view line;
    while (lines.next(line)) {
      if (rows.parse(line, lines.line_number(), row)) {
        row.line = lines.line_number();
        ++rows_read;
        return true;
      }
    }
    return false;
  }

  bool append_block(std::vector<VectorRow>& out, int threads) {
    const std::size_t before = out.size();
    while (out.size() == before) {
      const char *begin = nullptr, *end = nullptr;
      if (!lines.block(begin, end)) {
        // No whole line in the buffer (a line longer than it, a NUL byte, the end): one row, as
        // next() reads it.
        VectorRow row;
        if (!next(row)) return false;
        out.push_back(row);
        return true;
      }
      if (!blocks || blocks_threads != threads) {
        blocks = std::make_unique<BlockParser>(rows, threads);
        blocks_threads = threads;
      }
      std::unique_ptr<InputError> failed;
      const std::uint64_t n = blocks->parse(begin, end, lines.line_number() + 1, out, failed);
      lines.skip_block(end, n);
      rows_read += out.size() - before;
      if (failed) {
        error = std::move(failed);
        if (out.size() == before) throw *error;
      }
    }
    return true;
  }
  int blocks_threads = 0;
};

VectorReader::VectorReader(const std::string& path) {
  if (path == "-") {
    // Standard input, read in place (a pipe is read as it comes; nothing is reopened).
    auto in = std::make_unique<FdInputStream>(STDIN_FILENO, false);
    std::istream& ref = *in;
    impl_ = std::make_unique<Impl>(std::move(in), ref, kStdinName);
    return;
  }
  auto file = std::make_unique<std::ifstream>(path, std::ios::in | std::ios::binary);
  if (!file->is_open()) {
    const int err = errno;
    throw InputError(path, 0, "file",
                     std::string("cannot open for reading: ") +
                         (err != 0 ? std::strerror(err) : "unknown error"));
  }
  std::istream& in = *file;
  impl_ = std::make_unique<Impl>(std::move(file), in, path);
}

VectorReader::VectorReader(std::istream& in, std::string name)
    : impl_(std::make_unique<Impl>(nullptr, in, std::move(name))) {}

VectorReader::VectorReader(std::unique_ptr<std::istream> in, std::string name) {
  std::istream& ref = *in;
  impl_ = std::make_unique<Impl>(std::move(in), ref, std::move(name));
}

VectorReader::~VectorReader() = default;

const VectorHeader& VectorReader::header() const {
  return impl_->file.header;
}
const std::string& VectorReader::name() const {
  return impl_->lines.file();
}
bool VectorReader::next(VectorRow& row) {
  if (impl_->error) throw *impl_->error;
  try {
    return impl_->next(row);
  } catch (const InputError& e) {
    impl_->error = std::make_unique<InputError>(e);
    throw;
  }
}
bool VectorReader::next_block(std::vector<VectorRow>& rows, int threads) {
  rows.clear();
  return append_block(rows, threads);
}

bool VectorReader::append_block(std::vector<VectorRow>& rows, int threads) {
  if (impl_->error) throw *impl_->error;
  try {
    return impl_->append_block(rows, threads);
  } catch (const InputError& e) {
    if (!impl_->error) impl_->error = std::make_unique<InputError>(e);
    throw;
  }
}

std::uint64_t VectorReader::rows_read() const {
  return impl_->rows_read;
}

// ---- Writer ----------------------------------------------------------------------------------

struct VectorWriter::Impl {
  std::string where;  // the path, or "<stream>", for messages
  VectorHeader header;
  std::unique_ptr<AtomicOutputFile> file;
  std::ostream* out = nullptr;
  std::string buf;
  std::uint64_t rows = 0;
  bool committed = false;

  static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

  Impl(std::string w, const VectorHeader& h) : where(std::move(w)), header(h) {
    validate(header);
    buf.reserve(kFlushBytes + 256);
  }

  void write_header() {
    buf += magic_line();
    buf += "\neps ";
    append_double(buf, header.eps);
    // Only when not the default, so that files written before the line existed stay the same.
    if (header.display != DisplayEncoding::kLinear8) {
      buf += "\ndisplay ";
      buf += to_string(header.display);
    }
    buf += "\nlights ";
    append_int(buf, header.lights);
    buf += '\n';
    for (std::size_t i = 0; i < header.light_intensity.size(); ++i) {
      const auto& c = header.light_intensity[i];
      if (is_white(c)) continue;
      buf += "light ";
      append_int(buf, static_cast<std::int64_t>(i));
      for (int k = 0; k < 3; ++k) {
        buf += k == 0 ? ' ' : ',';
        append_double(buf, c[static_cast<std::size_t>(k)]);
      }
      buf += '\n';
    }
    for (const auto& m : header.materials) {
      buf += "material ";
      buf += m.name;
      buf += " specular=";
      for (int k = 0; k < 3; ++k) {
        if (k != 0) buf += ',';
        append_double(buf, m.specular[static_cast<std::size_t>(k)]);
      }
      buf += " lobe=";
      buf += to_string(m.lobe);
      if (m.shininess > 0) {
        buf += " shininess=";
        append_double(buf, m.shininess);
      }
      if (m.lobe == VectorLobe::kGaussian) {
        buf += " roughness=";
        append_double(buf, m.roughness);
      }
      buf += '\n';
    }
    buf += "columns t material";
    if (header.has_light) buf += " light";
    if (header.has_xy) buf += " x y";
    buf += "\ndata\n";
  }

  void flush() {
    out->write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
    if (!*out) throw OutputError("cannot write '" + where + "'");
  }

  void write(const VectorRow& r) {
    if (committed) throw std::logic_error("VectorWriter::write after commit()");
    const auto bad = [&](const std::string& msg) {
      throw std::invalid_argument("VectorWriter: row " + std::to_string(rows + 1) + ": " + msg);
    };
    if (!valid_t(r.t)) {
      bad("t = " + format_double(r.t) + " is not finite or outside " + t_range_text());
    }
    if (r.material >= header.materials.size()) {
      bad("material index " + std::to_string(r.material) + " out of range");
    }
    if (header.has_light) {
      if (!valid_light_index(r.light, header.lights)) {
        bad("light " + std::to_string(r.light) + " out of range");
      }
    } else if (r.light != 0) {
      bad("light " + std::to_string(r.light) + " but the header has no light column");
    }
    if (header.has_xy) {
      if (!valid_pixel(r.x) || !valid_pixel(r.y)) bad("pixel coordinates must be >= 0");
    } else if (r.x != -1 || r.y != -1) {
      bad("pixel coordinates given but the header has no x y columns");
    }
    append_double(buf, r.t);
    buf += ' ';
    buf += header.materials[r.material].name;
    if (header.has_light) {
      buf += ' ';
      append_int(buf, r.light);
    }
    if (header.has_xy) {
      buf += ' ';
      append_int(buf, r.x);
      buf += ' ';
      append_int(buf, r.y);
    }
    buf += '\n';
    ++rows;
    if (buf.size() >= kFlushBytes) flush();
  }

  void commit() {
    if (committed) throw std::logic_error("VectorWriter::commit called twice");
    flush();
    if (file) {
      file->commit();
    } else {
      out->flush();
      if (!*out) throw OutputError("cannot write '" + where + "'");
    }
    committed = true;
  }
};

VectorWriter::VectorWriter(const std::string& path, const VectorHeader& header)
    : impl_(std::make_unique<Impl>(path, header)) {
  impl_->file = std::make_unique<AtomicOutputFile>(path);
  impl_->out = &impl_->file->stream();
  impl_->write_header();
}

VectorWriter::VectorWriter(std::ostream& out, const VectorHeader& header, std::string name)
    : impl_(std::make_unique<Impl>(std::move(name), header)) {
  impl_->out = &out;
  impl_->write_header();
}

VectorWriter::~VectorWriter() = default;

void VectorWriter::write(const VectorRow& row) {
  impl_->write(row);
}
void VectorWriter::commit() {
  impl_->commit();
}
const VectorHeader& VectorWriter::header() const {
  return impl_->header;
}
std::uint64_t VectorWriter::rows_written() const {
  return impl_->rows;
}

}  // namespace glint
