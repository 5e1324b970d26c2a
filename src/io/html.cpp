#include "io/html.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace glint {
namespace {

// The page's behaviour, inline so that it works offline and from a file:// URL. A click on a
// heading sorts its table by that column (numbers by their data-v value, text otherwise), again
// for the reverse order. With #selftest in the URL the page checks itself once loaded and writes
// what it found into <pre id="selftest">, for a headless browser's dumped DOM
// (tests/cli/test_html_browser.cpp): each table's rows, a sort in both directions, every image
// decoded, and where the first image lies (for the screenshot's check).
constexpr const char* kScript = R"JS(
function glintSort(th) {
  var table = th.closest('table'), body = table.tBodies[0];
  var col = Array.prototype.indexOf.call(th.parentNode.children, th);
  var up = th.getAttribute('aria-sort') !== 'ascending';
  Array.prototype.forEach.call(th.parentNode.children, function (h) { h.removeAttribute('aria-sort'); });
  th.setAttribute('aria-sort', up ? 'ascending' : 'descending');
  var rows = Array.prototype.slice.call(body.rows);
  var key = function (r) { var c = r.cells[col]; return c && c.hasAttribute('data-v') ? parseFloat(c.getAttribute('data-v')) : (c ? c.textContent : ''); };
  rows.sort(function (a, b) {
    var x = key(a), y = key(b);
    var d = (typeof x === 'number' && typeof y === 'number') ? x - y : (typeof x === 'number' ? -1 : (typeof y === 'number' ? 1 : String(x).localeCompare(String(y))));
    return up ? d : -d;
  });
  rows.forEach(function (r) { body.appendChild(r); });
}
document.addEventListener('click', function (e) {
  var th = e.target.closest('table.sortable thead th');
  if (th) glintSort(th);
});
function glintSelfTest() {
  var out = [], ok = true;
  var tables = document.querySelectorAll('table.sortable');
  tables.forEach(function (t) { out.push('table ' + t.id + ' rows ' + t.tBodies[0].rows.length); });
  var sorted = false;
  tables.forEach(function (t) {
    if (sorted || t.tBodies[0].rows.length < 2) return;
    var heads = t.tHead.rows[0].cells;
    for (var c = 0; c < heads.length && !sorted; ++c) {
      var cells = Array.prototype.map.call(t.tBodies[0].rows, function (r) { return r.cells[c]; });
      if (!cells.every(function (x) { return x && x.hasAttribute('data-v'); })) continue;
      var values = function () { return Array.prototype.map.call(t.tBodies[0].rows, function (r) { return parseFloat(r.cells[c].getAttribute('data-v')); }); };
      var distinct = new Set(values()).size;
      if (distinct < 2) continue;
      heads[c].click();
      var a = values(), up = a.every(function (v, i) { return i === 0 || a[i - 1] <= v; });
      heads[c].click();
      var b = values(), down = b.every(function (v, i) { return i === 0 || b[i - 1] >= v; });
      out.push('sort ' + t.id + ' column ' + heads[c].textContent + ' ascending ' + (up ? 'ok' : 'FAIL') + ' descending ' + (down ? 'ok' : 'FAIL'));
      ok = ok && up && down;
      sorted = true;
    }
  });
  var imgs = document.images, decoded = 0;
  for (var i = 0; i < imgs.length; ++i) if (imgs[i].complete && imgs[i].naturalWidth > 0) ++decoded;
  out.push('images ' + imgs.length + ' decoded ' + decoded);
  ok = ok && decoded === imgs.length;
  out.push('svgs ' + document.querySelectorAll('svg').length);
  if (imgs.length > 0) {
    var r = imgs[0].getBoundingClientRect();
    out.push('image0 ' + [r.left + window.scrollX, r.top + window.scrollY, r.width, r.height].map(Math.round).join(' '));
  }
  out.push('selftest ' + (ok ? 'pass' : 'FAIL'));
  document.getElementById('selftest').textContent = out.join('\n') + '\n';
}
window.addEventListener('load', function () {
  // An image shown larger than it is keeps its pixels square and sharp: a blur would hide what
  // a pixel holds.
  Array.prototype.forEach.call(document.images, function (im) {
    if (im.naturalWidth < im.clientWidth) im.style.imageRendering = 'pixelated';
  });
  if (location.hash === '#selftest') glintSelfTest();
});
)JS";

constexpr const char* kStyle = R"CSS(
body { font-family: "DejaVu Sans", Arial, sans-serif; margin: 16px 24px; color: #222; background: #fff; }
h1 { font-size: 22px; } h2 { font-size: 18px; margin-top: 28px; } h3 { font-size: 15px; }
table { border-collapse: collapse; margin: 8px 0 16px; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 7px; text-align: left; vertical-align: top; }
td[data-v] { text-align: right; font-variant-numeric: tabular-nums; }
table.sortable thead th { cursor: pointer; background: #f0f0f0; user-select: none; }
th[aria-sort=ascending]::after { content: " \25B2"; } th[aria-sort=descending]::after { content: " \25BC"; }
caption { text-align: left; font-weight: bold; padding: 4px 0; }
pre { background: #f6f6f6; padding: 8px; overflow-x: auto; white-space: pre-wrap; word-break: break-all; }
.wide { overflow-x: auto; }
.gallery { display: flex; flex-wrap: wrap; gap: 12px; }
.gallery figure { flex: 0 1 420px; min-width: 240px; } .gallery img { width: 100%; }
figure { margin: 0; } figcaption { font-size: 12px; color: #555; }
figure img { max-width: 100%; border: 1px solid #ddd; }
figure.plot svg { max-width: 100%; height: auto; border: 1px solid #ddd; }
details { margin: 12px 0; } summary { cursor: pointer; font-weight: bold; }
)CSS";

bool plain_shell_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         std::string_view("_-./=:,+@%^").find(c) != std::string_view::npos;
}

void flatten(const nlohmann::json& v, const std::string& prefix, int depth,
             std::vector<std::pair<std::string, const nlohmann::json*>>& out) {
  if (v.is_object() && depth > 0 && !v.empty()) {
    for (const auto& [k, child] : v.items())
      flatten(child, prefix.empty() ? k : prefix + "." + k, depth - 1, out);
    return;
  }
  out.emplace_back(prefix, &v);
}

}  // namespace

std::string html_escape(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(bytes[k]); };
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned n = byte(i) << 16 | byte(i + 1) << 8 | byte(i + 2);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += kAlphabet[n >> 6 & 63];
    out += kAlphabet[n & 63];
  }
  if (i < bytes.size()) {
    const bool two = i + 1 < bytes.size();
    const unsigned n = byte(i) << 16 | (two ? byte(i + 1) << 8 : 0u);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += two ? kAlphabet[n >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

std::string shell_word(std::string_view word) {
  bool plain = !word.empty();
  for (char c : word) plain = plain && plain_shell_char(c);
  if (plain) return std::string(word);
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string shell_command(const std::vector<std::string>& argv) {
  std::string out;
  for (const std::string& w : argv) out += (out.empty() ? "" : " ") + shell_word(w);
  return out;
}

std::string reproduce_command(const HtmlRunInfo& run) {
  const std::string command = shell_command(run.argv);
  return run.cwd.empty() ? command : "cd " + shell_word(run.cwd) + " && " + command;
}

HtmlCell json_cell(const nlohmann::json& v) {
  if (v.is_number_integer() || v.is_number_unsigned()) return {v.dump(), true, v.get<double>()};
  if (v.is_number()) {
    const double d = v.get<double>();
    // Six significant digits read at a glance; the sort key and report.json keep every digit.
    return {fmt::format("{:.6g}", d), std::isfinite(d), d};
  }
  if (v.is_null()) return {"-"};
  if (v.is_string()) return {v.get<std::string>()};
  if (v.is_boolean()) return {v.get<bool>() ? "true" : "false"};
  return {v.dump()};
}

HtmlTable json_table(const std::string& id, const nlohmann::json& rows, int depth) {
  HtmlTable t;
  t.id = id;
  std::vector<std::vector<std::pair<std::string, const nlohmann::json*>>> leaves;
  for (const nlohmann::json& row : rows) {
    leaves.emplace_back();
    flatten(row, "", depth + 1, leaves.back());  // the row itself is not a level
    for (const auto& [name, value] : leaves.back())
      if (std::find(t.headings.begin(), t.headings.end(), name) == t.headings.end())
        t.headings.push_back(name);
  }
  for (const auto& row : leaves) {
    std::vector<HtmlCell> cells(t.headings.size());
    for (const auto& [name, value] : row) {
      const auto at = std::find(t.headings.begin(), t.headings.end(), name) - t.headings.begin();
      cells[static_cast<std::size_t>(at)] = json_cell(*value);
    }
    t.rows.push_back(std::move(cells));
  }
  return t;
}

HtmlPage::HtmlPage(const std::string& title) : title_(title) {
  heading(1, title);
}

void HtmlPage::heading(int level, std::string_view text) {
  body_ += fmt::format("<h{0}>{1}</h{0}>\n", level, html_escape(text));
}

void HtmlPage::paragraph(std::string_view text) {
  body_ += "<p>" + html_escape(text) + "</p>\n";
}

void HtmlPage::pre(std::string_view text, std::string_view id) {
  body_ += id.empty() ? std::string("<pre>") : "<pre id=\"" + html_escape(id) + "\">";
  body_ += html_escape(text) + "</pre>\n";
}

void HtmlPage::figures(const std::string& id,
                       const std::vector<std::pair<std::string, std::string>>& kv) {
  body_ += "<table class=\"figures\" id=\"" + html_escape(id) + "\"><tbody>\n";
  for (const auto& [k, v] : kv)
    body_ += "<tr><th>" + html_escape(k) + "</th><td>" + html_escape(v) + "</td></tr>\n";
  body_ += "</tbody></table>\n";
}

void HtmlPage::table(const HtmlTable& t) {
  // Wide tables (long specs) scroll on their own rather than widening the page.
  body_ += "<div class=\"wide\"><table class=\"sortable\" id=\"" + html_escape(t.id) + "\">";
  if (!t.caption.empty()) body_ += "<caption>" + html_escape(t.caption) + "</caption>";
  body_ += "\n<thead><tr>";
  for (const std::string& h : t.headings) body_ += "<th>" + html_escape(h) + "</th>";
  body_ += "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    body_ += "<tr>";
    for (const HtmlCell& c : row) {
      // %.17g reads back to the same double in the script's parseFloat.
      body_ += c.numeric ? fmt::format("<td data-v=\"{:.17g}\">", c.value) : std::string("<td>");
      body_ += html_escape(c.text) + "</td>";
    }
    body_ += "</tr>\n";
  }
  body_ += "</tbody></table></div>\n";
}

void HtmlPage::gallery(const std::vector<std::pair<std::string, std::string>>& pngs) {
  body_ += "<div class=\"gallery\">\n";
  for (const auto& [name, bytes] : pngs)
    body_ += "<figure><img alt=\"" + html_escape(name) + "\" src=\"data:image/png;base64," +
             base64(bytes) + "\"><figcaption>" + html_escape(name) + "</figcaption></figure>\n";
  body_ += "</div>\n";
}

void HtmlPage::raw_svg(std::string_view svg, std::string_view caption) {
  // Inline SVG is HTML, not XML: the declaration must go.
  if (svg.substr(0, 5) == "<?xml") svg.remove_prefix(std::min(svg.size(), svg.find("?>") + 2));
  body_ += "<figure class=\"plot\">";
  body_ += svg;
  body_ += "<figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
}

void HtmlPage::reproduce(const HtmlRunInfo& run) {
  heading(2, "Reproduce");
  pre(reproduce_command(run), "command");
  paragraph(run.version.empty() ? std::string("glint version unknown") : "glint " + run.version);
}

void HtmlPage::open_details(std::string_view summary) {
  body_ += "<details><summary>" + html_escape(summary) + "</summary>\n";
  ++details_open_;
}

void HtmlPage::close_details() {
  if (details_open_ == 0) return;
  body_ += "</details>\n";
  --details_open_;
}

std::string HtmlPage::finish() const {
  std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  out += "<meta name=\"generator\" content=\"glint\">\n";
  out += "<title>" + html_escape(title_) + "</title>\n<style>" + kStyle + "</style>\n";
  out += "<script>" + std::string(kScript) + "</script>\n</head>\n<body>\n" + body_;
  for (int i = 0; i < details_open_; ++i) out += "</details>\n";
  out += "<pre id=\"selftest\"></pre>\n</body>\n</html>\n";
  return out;
}

}  // namespace glint
