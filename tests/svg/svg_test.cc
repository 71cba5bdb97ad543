#include "common/svg/svg.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "tests/svg/xml.h"
#include "tests/test_util.h"

namespace animat::svg {
namespace {

TEST(XmlReaderTest, AcceptsWellFormedAndRejectsMalformedDocuments) {
  testing::XmlReader reader;
  std::optional<testing::XmlElement> ok = reader.Parse(
      "<?xml version=\"1.0\"?>\n<!-- c --><a x=\"1 &amp; 2\" y='3'><b/>t&lt;"
      "<c class=\"k\"><b class=\"k\"/></c></a>\n");
  ASSERT_TRUE(ok.has_value()) << reader.error();
  EXPECT_EQ(ok->Attribute("x"), "1 & 2");
  EXPECT_EQ(ok->text, "t<");
  EXPECT_EQ(ok->FindAll("b").size(), 2u);
  EXPECT_EQ(ok->FindAll("b", "k").size(), 1u);
  for (const char* bad :
       {"<a><b></a></b>", "<a>", "<a x=1/>", "<a x=\"1\" x=\"2\"/>",
        "<a>1 < 2</a>", "<a>fish & chips</a>", "<a/><b/>", "<a/>text",
        "<a x=\"<\"/>", "<a>&nbsp;</a>", "<a\"x\"/>", "",
        "<a x=\"1\"y=\"2\"/>"}) {
    EXPECT_FALSE(reader.Parse(bad).has_value()) << bad;
  }
}

TEST(SvgTest, NumbersHaveFixedDecimalsWithoutTrailingZeros) {
  EXPECT_EQ(Number(12.5), "12.5");
  EXPECT_EQ(Number(3.0), "3");
  EXPECT_EQ(Number(-0.254), "-0.25");
  EXPECT_EQ(Number(-0.001), "0");
  EXPECT_EQ(Number(0.123456, 4), "0.1235");
  EXPECT_EQ(Number(1234567.0, 0), "1234567");
  testing::FpTrapsOff traps_off;
  EXPECT_EQ(Number(std::numeric_limits<double>::quiet_NaN()), "0");
  EXPECT_EQ(Number(std::numeric_limits<double>::infinity()), "0");
}

TEST(SvgTest, EscapesMarkupInText) {
  EXPECT_EQ(Escape("a<b & \"c\" 'd'>"),
            "a&lt;b &amp; &quot;c&quot; &apos;d&apos;&gt;");
}

TEST(SvgTest, WritesAWellFormedDocumentAndClosesOpenGroups) {
  SvgWriter svg(200, 100);
  svg.Title("a < b");
  svg.BeginGroup("outer", "data-step=\"4\"");
  svg.Line({0, 0}, {10, 10}, "black", 1, "spring", "2,2");
  svg.Circle({5, 5}, 2, "red", "black", "cell");
  svg.BeginGroup("inner");
  svg.Polyline({{0, 0}, {1, 2}}, "blue", 1.5, "", "series", "x & y");
  svg.Arrow({0, 0}, {20, 0}, "black", 5, "distance");
  svg.Text({1, 2}, "Fish & \"chips\"", 12, "middle", -90);
  svg.Rect({0, 0}, 5, 5, "none", "grey");
  svg.Polygon({{0, 0}, {4, 0}, {0, 3}}, "#ff0000", "black", 0.5, "marker");
  const std::string text = svg.Finish();
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(text);
  ASSERT_TRUE(root.has_value()) << reader.error() << "\n" << text;
  EXPECT_EQ(root->name, "svg");
  EXPECT_EQ(root->Attribute("width"), "200");
  EXPECT_EQ(root->Attribute("xmlns"), "http://www.w3.org/2000/svg");
  EXPECT_EQ(root->FindAll("title")[0]->text, "a < b");
  ASSERT_EQ(root->FindAll("g", "outer").size(), 1u);
  EXPECT_EQ(root->FindAll("g", "outer")[0]->Attribute("data-step"), "4");
  EXPECT_EQ(root->FindAll("g", "inner").size(), 1u);
  EXPECT_EQ(root->FindAll("polyline", "series")[0]->Attribute("data-label"),
            "x & y");
  EXPECT_EQ(root->FindAll("polyline", "series")[0]->Attribute("points"),
            "0,0 1,2");
  EXPECT_EQ(root->FindAll("g", "distance")[0]->FindAll("polygon").size(), 1u);
  EXPECT_EQ(root->FindAll("text")[0]->text, "Fish & \"chips\"");
  const auto markers = root->FindAll("polygon", "marker");
  ASSERT_EQ(markers.size(), 1u);
  EXPECT_EQ(markers[0]->Attribute("points"), "0,0 4,0 0,3");
  EXPECT_EQ(markers[0]->Attribute("fill"), "#ff0000");
}

TEST(SvgTest, WrapsTextAtSpacesToAWidth) {
  EXPECT_EQ(WrapText("one two three", 1000, 10),
            (std::vector<std::string>{"one two three"}));
  // 6 pixels a character at size 10: "one two" is 42 wide.
  EXPECT_EQ(WrapText("one two three", 45, 10),
            (std::vector<std::string>{"one two", "three"}));
  EXPECT_EQ(WrapText("extraordinarily long", 30, 10),
            (std::vector<std::string>{"extraordinarily", "long"}));
  EXPECT_TRUE(WrapText("", 30, 10).empty());
  EXPECT_EQ(TextWidth("é–a", 10), 18);  // Characters, not bytes.
}

}  // namespace
}  // namespace animat::svg
