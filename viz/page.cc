#include "viz/page.h"

#include <string_view>

#include "viz/page_template.h"

namespace animat::viz {

Result<std::string> RenderPage(const v1::Trace& trace,
                               const PageOptions& options) {
  Result<std::string> data = PageDataJson(trace, options);
  if (!data.ok()) return data.status();
  const std::string_view page = kPageTemplate;
  const size_t at = page.find(kDataMarker);
  if (at == std::string_view::npos ||
      page.find(kDataMarker, at + 1) != std::string_view::npos) {
    return Status::Internal("the page template needs its data marker once");
  }
  std::string out;
  out.reserve(page.size() + data->size());
  out.append(page.substr(0, at));
  out.append(*data);
  out.append(page.substr(at + kDataMarker.size()));
  return out;
}

}  // namespace animat::viz
