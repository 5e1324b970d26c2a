// The HTML writer of the report pages (io/html.h): escaping, base64, shell quoting, JSON tables.
// The pages themselves, parsed and in a browser: tests/cli/html_report.py.
#include <gtest/gtest.h>

#include "io/html.h"

namespace glint {
namespace {

TEST(Html, EscapesEveryMarkupCharacter) {
  EXPECT_EQ(html_escape("<b a=\"x\" c='y'>&amp;</b>"),
            "&lt;b a=&quot;x&quot; c=&#39;y&#39;&gt;&amp;amp;&lt;/b&gt;");
  EXPECT_EQ(html_escape("plain text, é"), "plain text, é");
}

TEST(Html, Base64MatchesRfc4648) {
  // RFC 4648 section 10's vectors, every padding case.
  const std::pair<const char*, const char*> cases[] = {{"", ""},
                                                       {"f", "Zg=="},
                                                       {"fo", "Zm8="},
                                                       {"foo", "Zm9v"},
                                                       {"foob", "Zm9vYg=="},
                                                       {"fooba", "Zm9vYmE="},
                                                       {"foobar", "Zm9vYmFy"}};
  for (const auto& [in, out] : cases) EXPECT_EQ(base64(in), out) << in;
  EXPECT_EQ(base64(std::string("\xff\xfe\x00", 3)), "//4A");
}

TEST(Html, ShellWordsQuoteOnlyWhatTheShellWouldRead) {
  EXPECT_EQ(shell_word("traces/scenes/teapot.json"), "traces/scenes/teapot.json");
  EXPECT_EQ(shell_word("lut:bits=4..9"), "lut:bits=4..9");
  EXPECT_EQ(shell_word(""), "''");
  EXPECT_EQ(shell_word("lsb8<=1"), "'lsb8<=1'");
  EXPECT_EQ(shell_word("a b"), "'a b'");
  EXPECT_EQ(shell_word("it's"), "'it'\\''s'");
  EXPECT_EQ(shell_word("$HOME"), "'$HOME'");
  EXPECT_EQ(shell_command({"glint", "size", "--budget", "lsb8<=1"}),
            "glint size --budget 'lsb8<=1'");
  HtmlRunInfo run;
  run.argv = {"glint", "render", "x y.json"};
  run.cwd = "/tmp/a'b";
  EXPECT_EQ(reproduce_command(run), "cd '/tmp/a'\\''b' && glint render 'x y.json'");
}

TEST(Html, JsonTableFlattensObjectsAndUnionsColumns) {
  const nlohmann::json rows = nlohmann::json::parse(R"([
    {"unit": "lut", "error": {"max": 1.5, "parts": {"a": 1}}, "n": 3},
    {"unit": "hast", "extra": null, "n": 4}
  ])");
  const HtmlTable one = json_table("t", rows, 1);
  ASSERT_EQ(one.headings,
            (std::vector<std::string>{"error.max", "error.parts", "n", "unit", "extra"}));
  ASSERT_EQ(one.rows.size(), 2u);
  EXPECT_EQ(one.rows[0][0].text, "1.5");
  EXPECT_TRUE(one.rows[0][0].numeric);
  EXPECT_EQ(one.rows[0][1].text, "{\"a\":1}");  // deeper than `depth`: compact JSON
  EXPECT_EQ(one.rows[1][0].text, "");           // missing from the row
  EXPECT_FALSE(one.rows[1][0].numeric);
  EXPECT_EQ(one.rows[1][4].text, "-");  // null
  EXPECT_EQ(json_table("t", rows, 2).headings[1], "error.parts.a");
}

TEST(Html, PageEscapesWhatItIsGivenAndClosesWhatItOpens) {
  HtmlPage page("<title>");
  page.figures("f", {{"<k>", "<v>"}});
  HtmlTable t;
  t.id = "x\"y";
  t.headings = {"<h>"};
  t.rows = {{HtmlCell{"<c>", true, 2.5}}};
  page.table(t);
  page.open_details("<s>");
  page.gallery({{"<img>.png", "\x89PNG"}});
  const std::string html = page.finish();  // the details left open are closed here
  for (const char* raw :
       {"<title><", "<h1><", "<k>", "<v>", "<h>", "<c>", "<s>", "<img>.png", "x\"y"})
    EXPECT_EQ(html.find(raw), std::string::npos) << raw;
  EXPECT_NE(html.find("<h1>&lt;title&gt;</h1>"), std::string::npos);
  EXPECT_NE(html.find("<td data-v=\"2.5\">&lt;c&gt;</td>"), std::string::npos);
  EXPECT_NE(html.find("src=\"data:image/png;base64,iVBORw==\""), std::string::npos);
  EXPECT_NE(html.find("</details>\n<pre id=\"selftest\"></pre>\n</body>\n</html>\n"),
            std::string::npos);
}

}  // namespace
}  // namespace glint
