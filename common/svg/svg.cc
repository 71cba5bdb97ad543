#include "common/svg/svg.h"

#include <cmath>
#include <cstdio>

namespace animat::svg {

std::string Number(double value, int decimals) {
  if (!std::isfinite(value)) return "0";
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  std::string s = text;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

std::string Escape(std::string_view text) {
  std::string out;
  for (char c : text) {
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
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

double TextWidth(std::string_view text, double size) {
  int characters = 0;
  for (const char c : text) {
    // Every byte but UTF-8 continuation bytes starts a character.
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++characters;
  }
  return 0.6 * size * characters;
}

std::vector<std::string> WrapText(std::string_view text, double width,
                                  double size) {
  std::vector<std::string> lines;
  std::string line;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view word = text.substr(start, end - start);
    start = end + 1;
    if (word.empty()) continue;
    const std::string longer =
        line.empty() ? std::string(word) : line + " " + std::string(word);
    if (!line.empty() && TextWidth(longer, size) > width) {
      lines.push_back(line);
      line = std::string(word);
    } else {
      line = longer;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

namespace {

// Appends ` name="value"` (escaped) unless `value` is empty. Pieces are
// appended one by one: GCC 12 warns falsely (-Wrestrict) about chains of
// string temporaries.
void Attribute(std::string& out, std::string_view name,
               std::string_view value) {
  if (value.empty()) return;
  out.append(" ").append(name).append("=\"").append(Escape(value));
  out.append("\"");
}

void NumberAttribute(std::string& out, std::string_view name, double value) {
  out.append(" ").append(name).append("=\"").append(Number(value));
  out.append("\"");
}

void Points(std::string& out, const std::vector<Vec2>& points) {
  out.append(" points=\"");
  for (size_t i = 0; i < points.size(); ++i) {
    if (i > 0) out.append(" ");
    out.append(Number(points[i].x)).append(",").append(Number(points[i].y));
  }
  out.append("\"");
}

}  // namespace

SvgWriter::SvgWriter(double width, double height) {
  out_.append("<svg xmlns=\"http://www.w3.org/2000/svg\"");
  NumberAttribute(out_, "width", width);
  NumberAttribute(out_, "height", height);
  out_.append(" viewBox=\"0 0 ").append(Number(width)).append(" ");
  out_.append(Number(height)).append("\" font-family=\"sans-serif\">\n");
  out_.append("<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
}

void SvgWriter::BeginGroup(std::string_view css_class,
                           std::string_view attributes) {
  out_.append("<g");
  Attribute(out_, "class", css_class);
  if (!attributes.empty()) out_.append(" ").append(attributes);
  out_.append(">\n");
  ++open_groups_;
}

void SvgWriter::EndGroup() {
  if (open_groups_ == 0) return;
  out_.append("</g>\n");
  --open_groups_;
}

void SvgWriter::Line(Vec2 a, Vec2 b, std::string_view stroke, double width,
                     std::string_view css_class, std::string_view dash) {
  out_.append("<line");
  Attribute(out_, "class", css_class);
  NumberAttribute(out_, "x1", a.x);
  NumberAttribute(out_, "y1", a.y);
  NumberAttribute(out_, "x2", b.x);
  NumberAttribute(out_, "y2", b.y);
  Attribute(out_, "stroke", stroke);
  NumberAttribute(out_, "stroke-width", width);
  Attribute(out_, "stroke-dasharray", dash);
  out_.append("/>\n");
}

void SvgWriter::Circle(Vec2 centre, double radius, std::string_view fill,
                       std::string_view stroke, std::string_view css_class) {
  out_.append("<circle");
  Attribute(out_, "class", css_class);
  NumberAttribute(out_, "cx", centre.x);
  NumberAttribute(out_, "cy", centre.y);
  NumberAttribute(out_, "r", radius);
  Attribute(out_, "fill", fill);
  Attribute(out_, "stroke", stroke);
  out_.append("/>\n");
}

void SvgWriter::Rect(Vec2 corner, double width, double height,
                     std::string_view fill, std::string_view stroke) {
  out_.append("<rect");
  NumberAttribute(out_, "x", corner.x);
  NumberAttribute(out_, "y", corner.y);
  NumberAttribute(out_, "width", width);
  NumberAttribute(out_, "height", height);
  Attribute(out_, "fill", fill);
  Attribute(out_, "stroke", stroke);
  out_.append("/>\n");
}

void SvgWriter::Polyline(const std::vector<Vec2>& points,
                         std::string_view stroke, double width,
                         std::string_view dash, std::string_view css_class,
                         std::string_view label) {
  out_.append("<polyline");
  Attribute(out_, "class", css_class);
  Attribute(out_, "data-label", label);
  Points(out_, points);
  out_.append(" fill=\"none\"");
  Attribute(out_, "stroke", stroke);
  NumberAttribute(out_, "stroke-width", width);
  Attribute(out_, "stroke-dasharray", dash);
  out_.append("/>\n");
}

void SvgWriter::Polygon(const std::vector<Vec2>& points, std::string_view fill,
                        std::string_view stroke, double width,
                        std::string_view css_class) {
  out_.append("<polygon");
  Attribute(out_, "class", css_class);
  Points(out_, points);
  Attribute(out_, "fill", fill);
  Attribute(out_, "stroke", stroke);
  NumberAttribute(out_, "stroke-width", width);
  out_.append("/>\n");
}

void SvgWriter::Arrow(Vec2 a, Vec2 b, std::string_view colour, double head,
                      std::string_view css_class) {
  BeginGroup(css_class);
  Line(a, b, colour, 2);
  const Vec2 d = b - a;
  const double length = Length(d);
  if (length > 0) {
    const Vec2 u = d / length;
    const Vec2 n(-u.y, u.x);
    const Vec2 base = b - u * head;
    out_.append("<polygon");
    Points(out_, {b, base + n * (head / 2), base - n * (head / 2)});
    Attribute(out_, "fill", colour);
    out_.append("/>\n");
  }
  EndGroup();
}

void SvgWriter::Text(Vec2 at, std::string_view text, double size,
                     std::string_view anchor, double rotate,
                     std::string_view css_class) {
  out_.append("<text");
  Attribute(out_, "class", css_class);
  NumberAttribute(out_, "x", at.x);
  NumberAttribute(out_, "y", at.y);
  NumberAttribute(out_, "font-size", size);
  if (anchor != "start") Attribute(out_, "text-anchor", anchor);
  if (rotate != 0) {
    out_.append(" transform=\"rotate(").append(Number(rotate)).append(" ");
    out_.append(Number(at.x)).append(" ").append(Number(at.y)).append(")\"");
  }
  out_.append(">").append(Escape(text)).append("</text>\n");
}

void SvgWriter::Title(std::string_view text) {
  out_.append("<title>").append(Escape(text)).append("</title>\n");
}

std::string SvgWriter::Finish() {
  while (open_groups_ > 0) EndGroup();
  out_.append("</svg>\n");
  return std::move(out_);
}

}  // namespace animat::svg
