#include "figures/guidance_plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "tests/svg/xml.h"

namespace animat::figures {
namespace {

testing::XmlElement Parse(const std::string& svg) {
  testing::XmlReader reader;
  std::optional<testing::XmlElement> root = reader.Parse(svg);
  EXPECT_TRUE(root.has_value()) << reader.error();
  return root.value_or(testing::XmlElement{});
}

// K trials from the origin, each path heading half way to its source.
GuidancePicture Picture(int trials) {
  GuidancePicture picture;
  picture.title = "guidance";
  picture.decay_length = 10;
  for (int k = 0; k < trials; ++k) {
    const double angle = 2 * 3.141592653589793 * (k + 0.5) / trials;
    GuidanceTrialPath t;
    t.source = {30 * std::cos(angle), 30 * std::sin(angle)};
    for (int s = 0; s <= 10; ++s) t.path.push_back(t.source * (s / 20.0));
    t.caption = "trial " + std::to_string(k);
    picture.trials.push_back(t);
  }
  return picture;
}

double X(const std::string& point) { return std::atof(point.c_str()); }
double Y(const std::string& point) {
  return std::atof(point.substr(point.find(',') + 1).c_str());
}

TEST(GuidancePlotTest, HasOnePathAndOneSourcePerTrial) {
  const testing::XmlElement root = Parse(GuidanceSvg(Picture(4)));
  const auto trials = root.FindAll("g", "trial");
  ASSERT_EQ(trials.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(trials[k]->Attribute("data-trial"), std::to_string(k));
    EXPECT_EQ(trials[k]->FindAll("polyline", "path").size(), 1u);
    EXPECT_EQ(trials[k]->FindAll("circle", "source").size(), 1u);
    EXPECT_EQ(trials[k]->FindAll("circle", "gradient").size(), 1u);
  }
  EXPECT_EQ(root.FindAll("circle", "start").size(), 1u);
  EXPECT_EQ(root.FindAll("text", "legend").size(), 4u);
}

TEST(GuidancePlotTest, WorldAxesWithOneScale) {
  // K = 4: source 0 up and right of the start, source 2 down and left,
  // equally far (y grows downwards in SVG).
  const testing::XmlElement root = Parse(GuidanceSvg(Picture(4)));
  const auto start = root.FindAll("circle", "start");
  const auto sources = root.FindAll("circle", "source");
  ASSERT_EQ(start.size(), 1u);
  ASSERT_EQ(sources.size(), 4u);
  const double cx = std::atof(start[0]->Attribute("cx").c_str());
  const double cy = std::atof(start[0]->Attribute("cy").c_str());
  const double x0 = std::atof(sources[0]->Attribute("cx").c_str());
  const double y0 = std::atof(sources[0]->Attribute("cy").c_str());
  const double x2 = std::atof(sources[2]->Attribute("cx").c_str());
  const double y2 = std::atof(sources[2]->Attribute("cy").c_str());
  EXPECT_GT(x0, cx);
  EXPECT_LT(y0, cy);
  EXPECT_LT(x2, cx);
  EXPECT_GT(y2, cy);
  EXPECT_NEAR(x0 - cx, cx - x2, 0.02);
  EXPECT_NEAR(cx - x2, y2 - cy, 0.02);  // The same scale on both axes.
  // A path ends half way to its source.
  const std::string points =
      root.FindAll("polyline", "path")[0]->Attribute("points");
  const std::string last = points.substr(points.rfind(' ') + 1);
  EXPECT_NEAR(X(last), (cx + x0) / 2, 0.02);
  EXPECT_NEAR(Y(last), (cy + y0) / 2, 0.02);
}

TEST(GuidancePlotTest, ATrialWithoutAPathStillShowsItsSource) {
  GuidancePicture picture = Picture(3);
  picture.trials[1].path.clear();
  const testing::XmlElement root = Parse(GuidanceSvg(picture));
  EXPECT_EQ(root.FindAll("polyline", "path").size(), 2u);
  EXPECT_EQ(root.FindAll("circle", "source").size(), 3u);
}

}  // namespace
}  // namespace animat::figures
