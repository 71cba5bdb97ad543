#include "figures/contact_sheet.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "common/svg/svg.h"
#include "tests/svg/xml.h"

namespace animat::figures {
namespace {

SheetEntry Triangle(const std::string& heading, Vec2 displacement) {
  SheetEntry e;
  e.heading = heading;
  e.caption = "fitness 1";
  e.cells = {{10, 10}, {12, 10}, {11, 12}};
  e.springs = {{0, 1}, {1, 2}, {2, 0}};
  e.path = {{11, 10.5},
            {11 + displacement.x / 2, 10.5 + displacement.y / 2},
            {11 + displacement.x, 10.5 + displacement.y}};
  return e;
}

testing::XmlElement Parse(const std::string& svg) {
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(svg);
  EXPECT_TRUE(root.has_value()) << reader.error();
  return root.value_or(testing::XmlElement{});
}

TEST(ContactSheetTest, HasOnePictureOfEveryIndividualOnAGrid) {
  std::vector<SheetEntry> entries;
  for (int i = 0; i < 5; ++i) {
    entries.push_back(Triangle("generation " + std::to_string(i), {1, 0}));
  }
  entries.push_back(SheetEntry{"generation 5", "failed", {}, {}, {}});
  const testing::XmlElement root =
      Parse(ContactSheetSvg("best every generation", entries, 4));
  EXPECT_EQ(root.Attribute("width"), "720");  // 4 columns of 180.
  const auto pictures = root.FindAll("g", "individual");
  ASSERT_EQ(pictures.size(), 6u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(pictures[i]->FindAll("circle", "cell").size(), 3u);
    EXPECT_EQ(pictures[i]->FindAll("line", "spring").size(), 3u);
    EXPECT_EQ(pictures[i]->FindAll("polyline", "path").size(), 1u);
  }
  EXPECT_TRUE(pictures[5]->FindAll("circle", "cell").empty());
  EXPECT_TRUE(pictures[5]->FindAll("polyline", "path").empty());
  EXPECT_EQ(pictures[5]->FindAll("text")[0]->text, "generation 5");
}

TEST(ContactSheetTest, TurnsEachPathToRunRight) {
  // A path going straight down ends level with its start once turned.
  const testing::XmlElement root =
      Parse(ContactSheetSvg("t", {Triangle("down", {0, -3})}, 1));
  const auto paths = root.FindAll("polyline", "path");
  ASSERT_EQ(paths.size(), 1u);
  const std::string points = paths[0]->Attribute("points");
  const std::string first = points.substr(0, points.find(' '));
  const std::string last = points.substr(points.rfind(' ') + 1);
  const double x0 = std::atof(first.c_str());
  const double y0 = std::atof(first.substr(first.find(',') + 1).c_str());
  const double x1 = std::atof(last.c_str());
  const double y1 = std::atof(last.substr(last.find(',') + 1).c_str());
  EXPECT_NEAR(y1, y0, 0.01);
  EXPECT_GT(x1, x0 + 10);
}

TEST(ContactSheetTest, TheScaleFitsTheBodiesAndCutsLongPaths) {
  // A path of 100 radii would shrink a 2-radii body to a dot.
  SheetEntry far = Triangle("far", {100, 0});
  far.path.clear();
  for (int k = 0; k <= 100; ++k) far.path.push_back({11.0 + k, 10.5});
  const testing::XmlElement root = Parse(ContactSheetSvg("t", {far}, 1));
  const auto paths = root.FindAll("polyline", "path");
  ASSERT_EQ(paths.size(), 1u);
  std::istringstream points(paths[0]->Attribute("points"));
  int count = 0;
  for (std::string point; points >> point; ++count) {
    EXPECT_LE(std::atof(point.c_str()), 180) << point;  // Inside the frame.
  }
  EXPECT_GE(count, 2);
  EXPECT_LT(count, 10);
  // The cells are drawn large: radius 0.45 radii at > 10 pixels a radius.
  const auto cells = root.FindAll("circle", "cell");
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_GT(std::atof(cells[0]->Attribute("r").c_str()), 4.5);
}

// Every text fits the sheet, and a picture's heading and caption fit the
// picture: long ones are broken into lines, none of their words lost.
TEST(ContactSheetTest, EveryTextFitsItsPlaceWithNothingCut) {
  SheetEntry failed{"generation 12 of a long run",
                    "no individual with a fitness in this generation",
                    {},
                    {},
                    {}};
  for (const int columns : {1, 2, 4}) {
    SCOPED_TRACE(std::to_string(columns) + " columns");
    const std::vector<SheetEntry> entries = {Triangle("generation 0", {1, 0}),
                                             failed};
    const std::string title =
        "Best individual every 12 generations (seed 1234567)";
    const testing::XmlElement root =
        Parse(ContactSheetSvg(title, entries, columns));
    const double width = std::atof(root.Attribute("width").c_str());
    const double height = std::atof(root.Attribute("height").c_str());
    std::string words;
    for (const testing::XmlElement* text : root.FindAll("text")) {
      const double size = std::atof(text->Attribute("font-size").c_str());
      const double x = std::atof(text->Attribute("x").c_str());
      const double y = std::atof(text->Attribute("y").c_str());
      const double w = svg::TextWidth(text->text, size);
      const bool middle = text->Attribute("text-anchor") == "middle";
      const double left = middle ? x - w / 2 : x;
      EXPECT_GE(left, 0) << text->text;
      EXPECT_LE(left + w, width) << text->text;
      EXPECT_LE(y, height) << text->text;
      if (middle) {  // A picture's: within its column.
        const double column = std::floor(x / 180);
        EXPECT_GE(left, column * 180) << text->text;
        EXPECT_LE(left + w, (column + 1) * 180) << text->text;
      }
      words += text->text + " ";
    }
    for (const std::string& whole :
         {title, failed.heading, failed.caption,
          std::string("turned to run right, up to the frame.")}) {
      // Lines are joined by spaces: the whole text is there.
      EXPECT_NE(words.find(whole), std::string::npos) << whole << "\n" << words;
    }
  }
}

}  // namespace
}  // namespace animat::figures
