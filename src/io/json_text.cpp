#include "io/json_text.h"

#include <fstream>
#include <iterator>
#include <set>
#include <vector>

#include "io/input_error.h"

namespace glint {

namespace {

std::uint64_t line_at(const std::string& text, std::size_t byte) {
  if (byte > text.size()) byte = text.size();
  std::uint64_t line = 1;
  for (std::size_t i = 0; i < byte; ++i) line += text[i] == '\n';
  return line;
}

// Brackets outside strings, counted before parsing: nlohmann's parser itself is iterative, but a
// document nested thousands deep is never a glint input, and recursive code downstream (dump, the
// loaders) should not have to care.
void check_depth(const std::string& text, const std::string& file, int max_depth) {
  int depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > max_depth) {
        throw InputError(file, line_at(text, i), "json",
                         "nested deeper than " + std::to_string(max_depth) + " levels");
      }
    } else if (c == ']' || c == '}') {
      --depth;  // unbalanced brackets are the parser's to report
    }
  }
}

// The JSON path of the value being parsed, maintained from the parser's callback events.
class PathTracker {
 public:
  using Event = nlohmann::json::parse_event_t;

  // Returns the path of a duplicate key when `event` introduces one, else "".
  std::string on(Event event, const nlohmann::json& parsed) {
    switch (event) {
      case Event::object_start:
        enter_value();
        frames_.push_back({false, 0, {}, {}});
        break;
      case Event::array_start:
        enter_value();
        frames_.push_back({true, 0, {}, {}});
        break;
      case Event::object_end:
      case Event::array_end:
        frames_.pop_back();
        break;
      case Event::key:
        frames_.back().key = parsed.get<std::string>();
        if (!frames_.back().keys.insert(frames_.back().key).second) return path();
        break;
      case Event::value:
        enter_value();
        break;
    }
    return {};
  }

 private:
  struct Frame {
    bool array;
    std::size_t next;  // arrays: the index of the next element
    std::string key;   // objects: the current key
    std::set<std::string> keys;
  };

  void enter_value() {
    if (!frames_.empty() && frames_.back().array)
      frames_.back().key = std::to_string(frames_.back().next++);
  }

  std::string path() const {
    std::string out;
    for (const Frame& f : frames_) {
      if (f.array) {
        out += "[" + f.key + "]";
      } else {
        out += (out.empty() ? "" : ".") + f.key;
      }
    }
    return out;
  }

  std::vector<Frame> frames_;
};

}  // namespace

std::string read_text_file(const std::string& path, std::size_t max_bytes,
                           const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "file", "cannot open the " + what);
  std::string text;
  char buffer[65536];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > max_bytes) {
      throw InputError(path, 0, "file",
                       "larger than " + std::to_string(max_bytes >> 20) + " MiB: not a " + what);
    }
  }
  if (in.bad()) throw InputError(path, 0, "file", "read error");
  return text;
}

// The line of the first number literal in `text` that `message` quotes ('...'), 0 if none.
static std::uint64_t literal_line(const std::string& text, const std::string& message) {
  const auto open = message.find('\'');
  const auto close = open == std::string::npos ? open : message.find('\'', open + 1);
  if (close == std::string::npos || close == open + 1) return 0;
  const std::string literal = message.substr(open + 1, close - open - 1);
  const auto part_of_number = [](char c) {
    return (c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '+' || c == '-';
  };
  for (auto at = text.find(literal); at != std::string::npos; at = text.find(literal, at + 1)) {
    const std::size_t end = at + literal.size();
    if ((at == 0 || !part_of_number(text[at - 1])) &&
        (end == text.size() || !part_of_number(text[end])))
      return line_at(text, at);
  }
  return 0;
}

nlohmann::json parse_json_text(const std::string& text, const std::string& file, int max_depth) {
  check_depth(text, file, max_depth);
  PathTracker tracker;
  std::string duplicate;
  const auto callback = [&](int, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    std::string dup = tracker.on(event, parsed);
    if (duplicate.empty()) duplicate = std::move(dup);
    return true;
  };
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text, callback);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line L, column C: ...";
    // the line goes into the error's own field, the rest after the id is the message.
    std::string message = e.what();
    const auto colon = message.find(": ");
    if (colon != std::string::npos) message = message.substr(colon + 2);
    throw InputError(file, line_at(text, e.byte == 0 ? 0 : e.byte - 1), "json",
                     "not valid JSON: " + message);
  } catch (const nlohmann::json::exception& e) {
    // out_of_range.406: a number literal beyond a double ("1e999"); no position is given, but
    // the message quotes the literal: its first occurrence as a whole token gives the line.
    std::string message = e.what();
    const auto id_end = message.find("] ");
    if (id_end != std::string::npos) message = message.substr(id_end + 2);
    throw InputError(file, literal_line(text, message), "json", "not usable JSON: " + message);
  }
  if (!duplicate.empty()) throw InputError(file, 0, duplicate, "duplicate key");
  return doc;
}

}  // namespace glint
