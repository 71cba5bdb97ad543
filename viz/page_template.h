// The page of `animat render` (viz/page.html), compiled into the library
// by viz/embed_page.cmake.
#ifndef ANIMAT_VIZ_PAGE_TEMPLATE_H_
#define ANIMAT_VIZ_PAGE_TEMPLATE_H_

#include <string_view>

namespace animat::viz {

// The whole page, with kDataMarker once where the data goes.
extern const char kPageTemplate[];

// Stands for the page's data (a JSON value) in kPageTemplate.
inline constexpr std::string_view kDataMarker = "/*ANIMAT-DATA*/null";

}  // namespace animat::viz

#endif  // ANIMAT_VIZ_PAGE_TEMPLATE_H_
