// A small writer of SVG documents: elements are appended as text, numbers
// printed with a fixed number of decimals (the same text on every
// machine), text and attribute values escaped. Every figure of figures/
// is built with it; the accuracy report's plot (bench/accuracy) uses its
// escape and text width. Depends on common/base only.
//
// The functions are pure and thread-safe; an SvgWriter is not (a value
// type; one thread builds one document).
#ifndef ANIMAT_COMMON_SVG_SVG_H_
#define ANIMAT_COMMON_SVG_SVG_H_

#include <string>
#include <string_view>
#include <vector>

#include "common/base/vec2.h"

namespace animat::svg {

// `value` with at most `decimals` decimals, trailing zeros dropped ("12.5",
// "3", "-0.25"); non-finite values print as "0" (SVG has no NaN).
std::string Number(double value, int decimals = 2);

// `text` with &, <, >, " and ' replaced by entities.
std::string Escape(std::string_view text);

// About how wide `text` is, in pixels, at font `size` in the figures'
// sans-serif: 0.6 em per character (a UTF-8 code point), more than DejaVu
// Sans or Liberation Sans need for ordinary text.
double TextWidth(std::string_view text, double size);

// `text` broken at spaces into lines at most `width` pixels wide by
// TextWidth; a word wider than that has a line of its own. No lines for
// empty text.
std::vector<std::string> WrapText(std::string_view text, double width,
                                  double size);

class SvgWriter {
 public:
  // Starts a document of `width` × `height` pixels on a white background.
  SvgWriter(double width, double height);

  // <g class="..." [data-*]> ... </g>. `attributes` is raw text added to
  // the tag (already escaped), e.g. `data-step="40"`.
  void BeginGroup(std::string_view css_class, std::string_view attributes = "");
  void EndGroup();

  void Line(Vec2 a, Vec2 b, std::string_view stroke, double width,
            std::string_view css_class = "", std::string_view dash = "");
  void Circle(Vec2 centre, double radius, std::string_view fill,
              std::string_view stroke, std::string_view css_class = "");
  void Rect(Vec2 corner, double width, double height, std::string_view fill,
            std::string_view stroke);
  void Polyline(const std::vector<Vec2>& points, std::string_view stroke,
                double width, std::string_view dash, std::string_view css_class,
                std::string_view label);
  // A closed polygon through `points`.
  void Polygon(const std::vector<Vec2>& points, std::string_view fill,
               std::string_view stroke, double width,
               std::string_view css_class = "");
  // An arrow from `a` to `b` (a line and a filled head of `head` pixels).
  void Arrow(Vec2 a, Vec2 b, std::string_view colour, double head,
             std::string_view css_class);
  // `anchor`: "start", "middle" or "end". `rotate`: degrees about `at`.
  void Text(Vec2 at, std::string_view text, double size = 12,
            std::string_view anchor = "start", double rotate = 0,
            std::string_view css_class = "");
  // <title> of the document (shown by viewers; read by tests).
  void Title(std::string_view text);

  // The document, closed; the writer must not be used afterwards.
  std::string Finish();

 private:
  std::string out_;
  int open_groups_ = 0;
};

}  // namespace animat::svg

#endif  // ANIMAT_COMMON_SVG_SVG_H_
