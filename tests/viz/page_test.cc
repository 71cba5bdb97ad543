#include "viz/page.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/viz/trace_builder.h"
#include "viz/page_template.h"

namespace animat::viz {
namespace {

TEST(PageTest, ThePageHoldsItsDataInPlaceOfTheMarker) {
  PageOptions options;
  options.title = "triangle";
  Result<std::string> page = RenderPage(testing::TriangleTrace(), options);
  ASSERT_TRUE(page.ok()) << page.status().message();
  Result<std::string> data = PageDataJson(testing::TriangleTrace(), options);
  ASSERT_TRUE(data.ok());
  EXPECT_EQ(page->find(kDataMarker), std::string::npos);
  EXPECT_NE(page->find("const ANIMAT_DATA = " + *data + ";"),
            std::string::npos);
  EXPECT_EQ(page->rfind("<!doctype html>", 0), 0u);
  EXPECT_NE(page->find("</html>"), std::string::npos);
}

TEST(PageTest, ThePageLoadsNothing) {
  Result<std::string> page = RenderPage(testing::TriangleTrace(), {});
  ASSERT_TRUE(page.ok());
  // No address of any kind, nothing that fetches.
  for (const char* word :
       {"http:", "https:", "//cdn", "src=", "href=", "url(", "@import",
        "fetch(", "XMLHttpRequest", "import(", "<link", "<iframe", "<img"}) {
    EXPECT_EQ(page->find(word), std::string::npos) << word;
  }
}

TEST(PageTest, TheSameTraceGivesTheSamePage) {
  Result<std::string> a = RenderPage(testing::TriangleTrace(), {});
  Result<std::string> b = RenderPage(testing::TriangleTrace(), {});
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(*a, *b);
  v1::Trace moved = testing::TriangleTrace();
  moved.mutable_frames(5)->set_x(0, 5);
  Result<std::string> c = RenderPage(moved, {});
  ASSERT_TRUE(c.ok());
  EXPECT_NE(*a, *c);
}

TEST(PageTest, FailsAsTheDataDoes) {
  v1::Trace empty;
  Result<std::string> page = RenderPage(empty, {});
  ASSERT_FALSE(page.ok());
  EXPECT_EQ(page.status().message(),
            "the trace has nothing to show (status status_unspecified)");
}

}  // namespace
}  // namespace animat::viz
