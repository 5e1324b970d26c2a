#include "io/vcd_writer.h"

#include <pthread.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <cstring>
#include <ctime>
#include <map>
#include <stdexcept>

namespace glint::rtl {

namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

// Identifier codes: printable ASCII '!' .. '~' without '#' and '$' (which start time stamps and
// keywords, and could confuse simple readers): 92 characters, shortest codes first.
constexpr char kIdAlphabet[] =
    "!\"%&'()*+,-./"
    "0123456789:;<=>?@ABCDEFGHIJKLMNOPQRSTUVWXYZ[\\]^_`abcdefghijklmnopqrstuvwxyz{|}~";
constexpr int kIdChars = sizeof kIdAlphabet - 1;
static_assert(kIdChars == 92, "identifier alphabet");
// put_id copies 8 bytes whatever the id's length; changes() may write one 9-byte line it drops.
constexpr std::size_t kIdSlack = 16;

// "00000000" .. "11111111": the 8 binary digits of every byte, MSB first, in one flat array (so
// an 8-byte read starting inside an entry stays inside the array).
struct ByteDigits {
  std::array<char, 256 * 8 + 8> digits{};
  ByteDigits() {
    for (int b = 0; b < 256; ++b)
      for (int k = 0; k < 8; ++k) digits[8 * b + k] = ((b >> (7 - k)) & 1) ? '1' : '0';
  }
  const char* of(std::uint64_t byte) const { return digits.data() + 8 * byte; }
};
const ByteDigits kBytes;

int bit_length(std::uint64_t v) {
  return v == 0 ? 0 : 64 - __builtin_clzll(v);
}

// "00" .. "99".
struct DecimalPairs {
  std::array<char, 200> digits{};
  DecimalPairs() {
    for (int i = 0; i < 100; ++i) {
      digits[2 * i] = static_cast<char>('0' + i / 10);
      digits[2 * i + 1] = static_cast<char>('0' + i % 10);
    }
  }
};
const DecimalPairs kPairs;

// Writes up to 20 digits plus up to 19 bytes of scratch after them (overwritten later).
char* put_decimal(char* p, std::uint64_t v) {
  char tmp[40] = {};
  char* const end = tmp + 20;
  char* q = end;
  while (v >= 100) {
    q -= 2;
    std::memcpy(q, kPairs.digits.data() + 2 * (v % 100), 2);
    v /= 100;
  }
  if (v >= 10) {
    q -= 2;
    std::memcpy(q, kPairs.digits.data() + 2 * v, 2);
  } else {
    *--q = static_cast<char>('0' + v);
  }
  std::memcpy(p, q, 20);  // fixed size: no call
  return p + (end - q);
}

std::vector<std::string> split_name(const std::string& name) {
  std::vector<std::string> parts;
  std::size_t pos = 0;
  while (true) {
    const std::size_t dot = name.find('.', pos);
    parts.push_back(name.substr(pos, dot == std::string::npos ? std::string::npos : dot - pos));
    if (dot == std::string::npos) break;
    pos = dot + 1;
  }
  return parts;
}

// The scope tree of the header, children and variables in registration order.
struct Scope {
  std::string name;
  std::vector<std::size_t> vars;      // signal indices
  std::vector<std::size_t> children;  // indices into the node list
  std::map<std::string, std::size_t> by_name;
};

// Blocks SIGPIPE in this thread while writing to a pipe and discards the one the writes raised:
// when the reading process is gone, write() fails with EPIPE and the writer reports the error,
// instead of the default action killing the whole process. Nothing happens when the caller had
// SIGPIPE blocked already (then the signal is the caller's to handle).
class SigpipeGuard {
 public:
  explicit SigpipeGuard(bool active) {
    if (!active) return;
    sigemptyset(&pipe_set_);
    sigaddset(&pipe_set_, SIGPIPE);
    active_ = pthread_sigmask(SIG_BLOCK, &pipe_set_, &old_) == 0 && !sigismember(&old_, SIGPIPE);
  }
  ~SigpipeGuard() {
    if (!active_) return;
    sigset_t pending;
    if (sigpending(&pending) == 0 && sigismember(&pending, SIGPIPE)) {
      const timespec zero{0, 0};
      sigtimedwait(&pipe_set_, nullptr, &zero);
    }
    pthread_sigmask(SIG_SETMASK, &old_, nullptr);
  }
  SigpipeGuard(const SigpipeGuard&) = delete;
  SigpipeGuard& operator=(const SigpipeGuard&) = delete;

 private:
  bool active_ = false;
  sigset_t pipe_set_{}, old_{};
};

}  // namespace

VcdWriter::VcdWriter(std::string root_scope) : root_(std::move(root_scope)) {}

VcdWriter::~VcdWriter() {
  if (file_) {
    SigpipeGuard guard(pipe_);
    std::fclose(file_);
  }
}

void VcdWriter::check_name(const std::string& name) {
  if (header_done_)
    throw std::logic_error("VcdWriter: variables must be declared before the header");
  for (const std::string& part : split_name(name)) {
    if (part.empty() || part.find_first_of(" \t\r\n") != std::string::npos)
      throw std::invalid_argument("VcdWriter: bad signal name '" + name + "'");
  }
  for (const TracedSignal& s : signals_) {
    if (s.name == name) throw std::invalid_argument("VcdWriter: signal '" + name + "' repeated");
  }
}

VcdWriter::Var VcdWriter::next_var(int width) {
  Var v;
  std::size_t n = next_id_++;
  char tmp[8];
  int len = 0;
  do {
    tmp[len++] = kIdAlphabet[n % kIdChars];
    n /= kIdChars;
  } while (n != 0 && len < 7);
  if (n != 0) throw std::length_error("VcdWriter: too many signals");
  for (int k = 0; k < len; ++k) v.id[k] = tmp[len - 1 - k];
  v.id[len] = '\n';
  v.id_len = static_cast<std::uint8_t>(len);
  v.width = static_cast<std::uint8_t>(width);
  // "b" + width digits + " " + id + "\n" (scalar: digit + id + "\n").
  max_changes_bytes_ += static_cast<std::size_t>(width) + 3 + static_cast<std::size_t>(len);
  return v;
}

void VcdWriter::add_clock(const std::string& name) {
  if (has_clock_) throw std::invalid_argument("VcdWriter: one clock only");
  check_name(name);
  has_clock_ = true;
  clock_var_ = next_var(1);
  signals_.push_back({name, 1, false});
  is_bool_.push_back(true);
  order_.push_back(static_cast<std::size_t>(-1));
}

void VcdWriter::add_bool(const bool& value, const std::string& name) {
  check_name(name);
  order_.push_back(bools_.size());
  is_bool_.push_back(true);
  bools_.push_back({&value, value, next_var(1)});
  signals_.push_back({name, 1, false});
}

void VcdWriter::add_bits(const std::uint64_t& value, int width, bool is_signed,
                         const std::string& name, int frac_bits) {
  if (width < 1 || width > 64)
    throw std::invalid_argument("VcdWriter: width of '" + name + "' must be 1..64");
  check_name(name);
  const std::uint64_t mask = width == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << width) - 1;
  order_.push_back(bits_.size());
  is_bool_.push_back(false);
  bits_.push_back({&value, mask, value & mask, next_var(width)});
  signals_.push_back({name, width, is_signed, frac_bits});
}

void VcdWriter::open(std::FILE* file, bool pipe) {
  if (!file) throw std::invalid_argument("VcdWriter: no file");
  if (file_) {
    SigpipeGuard guard(pipe_);
    std::fclose(file_);
  }
  file_ = file;
  pipe_ = pipe;
  // Every write already goes out in large blocks from buffer_; unbuffered, a pipe's write errors
  // surface in the fwrite that the guard covers rather than in a later hidden flush.
  if (pipe_) std::setvbuf(file_, nullptr, _IONBF, 0);
  failed_ = false;
  error_ = 0;
  capacity_ = std::max(kBufferBytes, 2 * (max_changes_bytes_ + kIdSlack) + 64);
  buffer_ = std::make_unique<char[]>(capacity_);
  pos_ = 0;
  flushed_ = 0;
  wrote_time_ = false;
  last_time_ = 0;
  tally_.reset();
}

void VcdWriter::flush() {
  if (pos_ == 0) return;
  if (tally_) tally_->feed(buffer_.get(), pos_);
  if (file_) {
    SigpipeGuard guard(pipe_);
    if (std::fwrite(buffer_.get(), 1, pos_, file_) != pos_) fail(errno);
  }
  flushed_ += pos_;
  pos_ = 0;
}

void VcdWriter::reserve(std::size_t bytes) {
  if (capacity_ - pos_ < bytes) flush();
  if (capacity_ < bytes) {
    // A header (or one sample) larger than the buffer.
    capacity_ = bytes;
    buffer_ = std::make_unique<char[]>(capacity_);
  }
}

void VcdWriter::put(const char* s, std::size_t n) {
  reserve(n);
  std::memcpy(buffer_.get() + pos_, s, n);
  pos_ += n;
}

char* VcdWriter::put_id(char* p, const Var& v) {
  std::memcpy(p, v.id, 8);  // the id and its '\n' (the rest is overwritten by the next write)
  return p + v.id_len + 1;
}

char* VcdWriter::put_bool(char* p, bool value, const Var& v) {
  *p++ = value ? '1' : '0';
  return put_id(p, v);
}

char* VcdWriter::put_bits(char* p, std::uint64_t value, const Var& v) {
  if (v.width == 1) return put_bool(p, value != 0, v);
  *p++ = 'b';
  // Digits without leading zeros, most significant first, in fixed 8-byte copies (no calls): the
  // top byte's k significant digits (its copy runs on into the next table entry; the excess is
  // overwritten), then whole bytes.
  const int n = value == 0 ? 1 : bit_length(value);
  const int full = (n - 1) / 8;  // whole bytes below the top one
  const int k = n - 8 * full;    // 1..8
  std::memcpy(p, kBytes.of((value >> (8 * full)) & 0xff) + (8 - k), 8);
  p += k;
  for (int i = full - 1; i >= 0; --i) {
    std::memcpy(p, kBytes.of((value >> (8 * i)) & 0xff), 8);
    p += 8;
  }
  *p++ = ' ';
  return put_id(p, v);
}

void VcdWriter::header(const std::string& timescale_unit, const std::string& version) {
  std::string h;
  char date[64] = "";
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  if (localtime_r(&now, &tm)) std::strftime(date, sizeof date, "%b %d, %Y %H:%M:%S", &tm);
  h += "$date\n  " + std::string(date) + "\n$end\n";
  h += "$version\n  " + version + "\n$end\n";
  h += "$timescale\n  1 " + timescale_unit + "\n$end\n";

  std::vector<Scope> nodes(1);
  nodes[0].name = root_;
  for (std::size_t i = 0; i < signals_.size(); ++i) {
    const std::vector<std::string> parts = split_name(signals_[i].name);
    std::size_t node = 0;
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
      const auto it = nodes[node].by_name.find(parts[k]);
      if (it != nodes[node].by_name.end()) {
        node = it->second;
        continue;
      }
      const std::size_t child = nodes.size();
      nodes[node].by_name.emplace(parts[k], child);
      nodes[node].children.push_back(child);
      nodes.emplace_back();
      nodes.back().name = parts[k];
      node = child;
    }
    nodes[node].vars.push_back(i);
  }
  auto var_of = [&](std::size_t i) -> const Var& {
    if (order_[i] == static_cast<std::size_t>(-1)) return clock_var_;
    return is_bool_[i] ? bools_[order_[i]].var : bits_[order_[i]].var;
  };
  // Variables first, then the sub-scopes (as SystemC's writer lays them out).
  auto emit = [&](auto&& self, std::size_t n) -> void {
    const Scope& s = nodes[n];
    const bool named = !s.name.empty();
    if (named) h += "$scope module " + s.name + " $end\n";
    for (std::size_t i : s.vars) {
      const TracedSignal& sig = signals_[i];
      const Var& v = var_of(i);
      h += "$var wire " + std::to_string(sig.width) + " " + std::string(v.id, v.id_len) + " " +
           split_name(sig.name).back();
      if (sig.width > 1) h += " [" + std::to_string(sig.width - 1) + ":0]";
      h += " $end\n";
    }
    for (std::size_t c : s.children) self(self, c);
    if (named) h += "$upscope $end\n";
  };
  emit(emit, 0);
  h += "$enddefinitions $end\n";
  put(h);
  header_done_ = true;
}

void VcdWriter::time(std::uint64_t t) {
  if (wrote_time_ && t <= last_time_) {
    if (t == last_time_) return;
    throw std::logic_error("VcdWriter: time going backwards");
  }
  reserve(48);
  char* p = buffer_.get() + pos_;
  *p++ = '#';
  p = put_decimal(p, t);
  *p++ = '\n';
  pos_ = static_cast<std::size_t>(p - buffer_.get());
  last_time_ = t;
  wrote_time_ = true;
}

void VcdWriter::dump_all(std::uint64_t t, bool clock_level) {
  time(t);
  put("$dumpvars\n", 10);
  reserve(max_changes_bytes_ + kIdSlack);
  char* p = buffer_.get() + pos_;
  if (has_clock_) p = put_bool(p, clock_level, clock_var_);
  clock_level_ = clock_level;
  for (BoolVar& b : bools_) {
    b.last = *b.value;
    p = put_bool(p, b.last, b.var);
  }
  for (BitsVar& b : bits_) {
    b.last = *b.value & b.mask;
    p = put_bits(p, b.last, b.var);
  }
  pos_ = static_cast<std::size_t>(p - buffer_.get());
  put("$end\n", 5);
}

void VcdWriter::clock(bool level) {
  if (!has_clock_ || level == clock_level_) return;
  clock_level_ = level;
  reserve(16);
  pos_ =
      static_cast<std::size_t>(put_bool(buffer_.get() + pos_, level, clock_var_) - buffer_.get());
}

void VcdWriter::changes() {
  reserve(max_changes_bytes_ + kIdSlack);
  char* p = buffer_.get() + pos_;
  // 1-bit values without a branch: the line is always written, and kept only if changed.
  for (BoolVar& b : bools_) {
    const bool v = *b.value;
    *p = static_cast<char>('0' + v);
    std::memcpy(p + 1, b.var.id, 8);
    p += (v != b.last) ? b.var.id_len + 2 : 0;
    b.last = v;
  }
  for (BitsVar& b : bits_) {
    const std::uint64_t v = *b.value & b.mask;
    if (v != b.last) {
      b.last = v;
      p = put_bits(p, v, b.var);
    }
  }
  pos_ = static_cast<std::size_t>(p - buffer_.get());
}

bool VcdWriter::close(std::uint64_t end_time) {
  if (!file_) return !failed_;
  if (!wrote_time_ || end_time > last_time_) time(end_time);
  flush();
  {
    SigpipeGuard guard(pipe_);
    if (std::fclose(file_) != 0) fail(errno);
  }
  file_ = nullptr;
  buffer_.reset();
  capacity_ = 0;
  return !failed_;
}

}  // namespace glint::rtl
