// A small HTML writer for glint's reports (render, sweep, size --html): one self-contained page,
// its images as data: URIs, tables sortable by a click on a heading, no script or style from the
// network. Every text and attribute value goes through html_escape, and elements are closed by
// the writer itself, so a hostile scene name or path cannot break out of its element.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

// Escapes &, <, >, " and ' (text and attribute values alike).
std::string html_escape(std::string_view s);
// RFC 4648 base64 with padding.
std::string base64(std::string_view bytes);
// One word quoted for a POSIX shell: as is when it is made only of characters no shell treats
// specially, else in single quotes ('\'' for a quote inside).
std::string shell_word(std::string_view word);
// The words joined by spaces, each shell_word.
std::string shell_command(const std::vector<std::string>& argv);

// Facts of a run its report does not hold: the command line and its folder, glint's version, and
// key figures of the input (e.g. a scene's eps), shown as given.
struct HtmlRunInfo {
  std::vector<std::string> argv;
  std::string cwd;
  std::string version;
  std::vector<std::pair<std::string, std::string>> figures;
};
// The command that reproduces a run: `cd CWD && ARGV...`, every word quoted for a POSIX shell.
std::string reproduce_command(const HtmlRunInfo& run);

// A cell of an HtmlTable: its text, and for a number the value it sorts by (data-v).
struct HtmlCell {
  std::string text;
  bool numeric = false;
  double value = 0;
};
// A JSON value as a cell: integers whole, other numbers to 6 significant digits, null as "-",
// strings as they are, anything else as compact JSON.
HtmlCell json_cell(const nlohmann::json& v);

struct HtmlTable {
  std::string id;       // the element's id (tests and the self-test find tables by it)
  std::string caption;  // may be empty
  std::vector<std::string> headings;
  std::vector<std::vector<HtmlCell>> rows;
};

// The leaves of an array of objects as a table: one column per scalar leaf, nested objects
// flattened to dotted names ("image_error.max_lsb") in the order they first occur; arrays and
// objects deeper than `depth` levels are one cell of compact JSON. A key missing from a row is "".
HtmlTable json_table(const std::string& id, const nlohmann::json& rows, int depth = 2);

// The page, written in order. Every method escapes what it is given except raw_svg (the caller's
// SVG document, its XML declaration dropped).
class HtmlPage {
 public:
  explicit HtmlPage(const std::string& title);
  void heading(int level, std::string_view text);
  void paragraph(std::string_view text);
  void pre(std::string_view text, std::string_view id = {});
  // Key figures: a two-column table of name and value (not sortable).
  void figures(const std::string& id, const std::vector<std::pair<std::string, std::string>>& kv);
  void table(const HtmlTable& t);
  // PNGs (file name, bytes) side by side, each a data: URI captioned with its name.
  void gallery(const std::vector<std::pair<std::string, std::string>>& pngs);
  void raw_svg(std::string_view svg, std::string_view caption);
  // "Reproduce": the command (id "command") and glint's version.
  void reproduce(const HtmlRunInfo& run);
  // Opens and closes <details> (a collapsed section headed by `summary`).
  void open_details(std::string_view summary);
  void close_details();
  // The whole document: the head (style, the sort script), the body written so far, the
  // self-test's <pre id="selftest"> and </html>.
  std::string finish() const;

 private:
  std::string title_, body_;
  int details_open_ = 0;
};

}  // namespace glint
